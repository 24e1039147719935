// fuzz_targets.hpp - the fuzzed entry points. Each fuzz_*.cpp defines one;
// under libFuzzer (VKFUSE_LIBFUZZER) it also defines LLVMFuzzerTestOneInput
// calling it, and in the normal build replay_test.cpp calls each on
// every committed corpus and regression input.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace vkfuse::fuzz {

// Each returns 0 and aborts on a broken contract: anything but success or a
// vkfuse::Error, an Error of an unexpected kind, or a message that does not
// start with the input's name.
int png(const std::uint8_t* data, std::size_t size);
int npy(const std::uint8_t* data, std::size_t size);
int args(const std::uint8_t* data, std::size_t size);
int mcap(const std::uint8_t* data, std::size_t size);
int ws(const std::uint8_t* data, std::size_t size);

// A contract violation: say which, then abort so libFuzzer keeps the input.
[[noreturn]] inline void violated(const char* what, const char* detail) {
    std::fprintf(stderr, "fuzz contract violated: %s: %s\n", what, detail);
    std::abort();
}

}  // namespace vkfuse::fuzz

#ifdef VKFUSE_LIBFUZZER
#define VKFUSE_FUZZ_ENTRY(fn) \
    extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { return fn(data, size); }
#else
#define VKFUSE_FUZZ_ENTRY(fn)
#endif

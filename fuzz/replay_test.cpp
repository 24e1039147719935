// Replays every committed fuzz input - the seed corpora and each input that
// once broke a target (regressions/) - through the fuzz entry points, built
// without libFuzzer, as part of the normal test run. A target aborts on a
// broken contract, which fails this test; the file being replayed is printed
// first so the log names it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace vkfuse::fuzz {
namespace {

std::vector<std::filesystem::path> inputs_of(const std::string& target) {
    std::vector<std::filesystem::path> files;
    for (const char* kind : {"corpus", "regressions"}) {
        const std::filesystem::path dir = std::filesystem::path(VKFUSE_FUZZ_DIR) / kind / target;
        if (!std::filesystem::exists(dir)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(dir))
            if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::size_t replay(const std::string& target, int (*entry)(const std::uint8_t*, std::size_t)) {
    const std::vector<std::filesystem::path> files = inputs_of(target);
    for (const auto& path : files) {
        std::printf("replaying %s\n", path.c_str());
        std::fflush(stdout);
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        EXPECT_EQ(entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), 0) << path;
    }
    return files.size();
}

// Each target has a seed corpus; an empty one would mean the path is wrong.
TEST(FuzzReplay, Png) { EXPECT_GE(replay("png", png), 5u); }
TEST(FuzzReplay, Npy) { EXPECT_GE(replay("npy", npy), 5u); }
TEST(FuzzReplay, Args) { EXPECT_GE(replay("args", args), 5u); }

}  // namespace
}  // namespace vkfuse::fuzz

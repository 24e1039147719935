// io/memory_available.hpp - how much memory this process may still take, so a
// command can refuse work that cannot fit (naming its inputs) before it
// decodes a pixel, instead of being killed by the OOM killer without a word.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace vkfuse::io {

struct MemoryAvailable {
    std::uint64_t bytes = 0;
    std::string source;  // which figure is the smallest: "MemAvailable", "RLIMIT_AS", ...
};

// The smallest of what the system reports, each where it is set and readable:
// - MemAvailable from /proc/meminfo;
// - RLIMIT_AS minus the process's address space (VmSize), RLIMIT_DATA minus
//   its data segment (VmData);
// - the memory cgroup's limit minus its usage (the inactive file cache counts
//   as free), for this cgroup and each ancestor: cgroup v2 memory.max and
//   memory.current, or cgroup v1 memory.limit_in_bytes and usage_in_bytes;
// - VKFUSE_MEMORY_LIMIT, when set: a byte count with an optional binary
//   suffix (K, M, G, T; "KiB", "GB" ... are read as the same), which lowers
//   the figure: to test the refusal, or to keep vkfuse below a share of the
//   machine. An unparsable value throws Error(InvalidArgument) naming it.
// nullopt when nothing at all can be read (no /proc): no limit is known.
std::optional<MemoryAvailable> available_memory();

// VKFUSE_MEMORY_LIMIT's grammar: "4G" -> 4 << 30; nullopt for anything else.
std::optional<std::uint64_t> parse_byte_count(std::string_view text);

// "16.0 GiB", "512 MiB", "12 KiB": the unit that keeps 1..1023 of it, with
// decimals digits after the point from GiB up.
std::string memory_text(double bytes, int decimals = 1);

}  // namespace vkfuse::io

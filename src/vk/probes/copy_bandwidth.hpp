// The device's buffer-to-buffer copy bandwidth, measured, so a benchmark can
// say what fraction of it a plan's uploads and readbacks use.
#pragma once
#include <cstdint>

#include "vkfuse/vk/context.hpp"

namespace vkfuse::vk {

struct CopyBandwidth {
    std::uint64_t bytes = 0;  // bytes per copy
    double seconds = 0;       // median time of one copy
    bool device_timed = false;  // timestamp queries (true) or host clock around submit + wait
    double bytes_per_second() const { return seconds > 0 ? double(bytes) / seconds : 0.0; }
};

// Copies `bytes` with vkCmdCopyBuffer from a host-visible upload buffer (the
// memory Plan::run writes frames into) to a device-local buffer, once to warm
// up and then `repeats` times; returns the median. Throws Error(Device).
CopyBandwidth measure_copy_bandwidth(Context& context, std::uint64_t bytes = std::uint64_t(64) << 20, int repeats = 9);

}  // namespace vkfuse::vk

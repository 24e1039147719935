// A byte range of one device buffer: how kernels are handed their buffers.
// Bound kernels see it through a descriptor (buffer, offset, bytes), the
// device-address variants through its address; Recorder::dispatch picks.
#pragma once
#include <cstdint>

#include "vk/engine/api.hpp"

namespace vkfuse::vk {

struct DeviceSpan {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;  // bytes into buffer
    VkDeviceSize bytes = 0;
    VkDeviceAddress base = 0;  // device address of the buffer's first byte

    VkDeviceAddress address() const { return base + offset; }
    // The part starting `from` bytes in, `count` bytes long (to the end when 0).
    DeviceSpan sub(VkDeviceSize from, VkDeviceSize count = 0) const {
        return {buffer, offset + from, count ? count : bytes - from, base};
    }
    // The same for float (4-byte) elements.
    DeviceSpan floats(std::uint64_t from, std::uint64_t count = 0) const { return sub(from * 4, count * 4); }
};

}  // namespace vkfuse::vk

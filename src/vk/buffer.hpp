// A VkBuffer with its own memory, addressed from shaders by device address.
#pragma once
#include <cstdint>

#include "vk/context_impl.hpp"
#include "vk/device_span.hpp"

namespace vkfuse::vk {

enum class MemoryUse {
    Device,    // working storage the host never touches
    Upload,    // host writes, device reads (device-local when the host can see it)
    Readback,  // device writes, host reads (host-cached when available)
};

class Buffer {
public:
    Buffer() = default;
    Buffer(Context::Impl& ctx, VkDeviceSize bytes, MemoryUse use);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceAddress address() const { return address_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }  // null for MemoryUse::Device
    DeviceSpan span() const { return {buffer_, 0, size_, address_}; }

private:
    Context::Impl* ctx_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceAddress address_ = 0;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;

    void release();
};

}  // namespace vkfuse::vk

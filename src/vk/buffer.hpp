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
    // Takes buffer and memory (bound, mapped at `mapped` or not) to destroy them.
    static Buffer adopt(Context::Impl& ctx, VkBuffer buffer, VkDeviceMemory memory, VkDeviceSize bytes, void* mapped);
    // bytes from offset of a buffer someone else owns (a caller's): used,
    // never destroyed here.
    static Buffer borrow(Context::Impl& ctx, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize bytes);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceMemory memory() const { return memory_; }  // null for a borrowed range
    VkDeviceAddress address() const { return address_ + offset_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }  // null for MemoryUse::Device
    DeviceSpan span() const { return {buffer_, offset_, size_, address_}; }

private:
    Context::Impl* ctx_ = nullptr;  // null for a borrowed range: nothing to release
    VkDeviceSize offset_ = 0;       // a borrowed range's start in its buffer
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceAddress address_ = 0;  // of the buffer's first byte
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;

    void release();
};

}  // namespace vkfuse::vk

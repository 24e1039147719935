// A VkBuffer with its own memory, bound to kernels through descriptors or
// reached by device address.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "vk/engine/context_impl.hpp"
#include "vk/engine/device_span.hpp"

namespace vkfuse::vk {

// What a buffer is for, and so which memory it takes (the first type of the
// first preference that has room; a full heap falls back to the next):
enum class MemoryUse {
    Device,    // working storage the host never touches: device-local, else any
    Upload,    // host writes, device reads: device-local host-visible coherent,
               // else host-visible coherent (system memory on a discrete GPU)
    Readback,  // device writes, host reads: host-visible cached, coherent or not
               // (invalidate() before reading), else host-visible
};

// lavapipe's memory is a host mapping: where mmap fails (an address space
// limit) it still reports success, and a mapping of the memory reads
// MAP_FAILED, all ones. For such a mapping this throws OutOfMemory
// "<subject>: <bytes> bytes reported allocated that the driver could not back
// (out of memory)"; every vkMapMemory of the library's checks its result here.
void check_mapping_backed(const void* mapped, VkDeviceSize bytes, const std::string& subject);

class Buffer {
public:
    Buffer() = default;
    Buffer(Context::Impl& ctx, VkDeviceSize bytes, MemoryUse use);
    // Takes buffer and memory (allocated through ctx.memory_types as `type`,
    // `allocation` bytes; bound, mapped at `mapped` or not) to destroy them.
    static Buffer adopt(Context::Impl& ctx, VkBuffer buffer, VkDeviceMemory memory, std::uint32_t type,
                        VkDeviceSize allocation, VkDeviceSize bytes, void* mapped);
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
    std::uint32_t heap() const;  // the heap its memory came from
    bool device_local() const;   // its memory type is DEVICE_LOCAL
    // Before the host reads what the device wrote (after the fence): makes it
    // visible in mapped() where the memory is not host-coherent.
    void invalidate() const;

    // Usage flags of every buffer the library makes (device addresses where
    // the context has them).
    static VkBufferUsageFlags usage(const Context::Impl& ctx);

private:
    Context::Impl* ctx_ = nullptr;  // null for a borrowed range: nothing to release
    VkDeviceSize offset_ = 0;       // a borrowed range's start in its buffer
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceAddress address_ = 0;  // of the buffer's first byte
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
    std::uint32_t type_ = 0;         // visible memory type (ctx.memory_types)
    VkDeviceSize allocation_ = 0;    // bytes allocated
    bool coherent_ = true;           // host-coherent: no invalidation needed
    void* memory_mapping_ = nullptr;  // the memory's own mapping where mapped_ is a shadow
    std::unique_ptr<std::byte[]> shadow_;  // a simulated non-coherent type's host copy

    void release();
};

}  // namespace vkfuse::vk

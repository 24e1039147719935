#include "vk/buffer.hpp"

#include <cstdint>
#include <string>
#include <utility>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

VkDeviceAddress device_address(Context::Impl& ctx, VkBuffer buffer) {
    VkBufferDeviceAddressInfo bai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    bai.buffer = buffer;
    return ctx.api->vkGetBufferDeviceAddress(ctx.device, &bai);
}

}  // namespace

Buffer::Buffer(Context::Impl& ctx, VkDeviceSize bytes, MemoryUse use) : ctx_(&ctx), size_(bytes) {
    auto& api = *ctx.api;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = bytes < 256 ? 256 : bytes;  // never a zero-sized buffer
    bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;  // a skipping plan's dispatch arguments
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(api.vkCreateBuffer(ctx.device, &bci, nullptr, &buffer_), "vkCreateBuffer");
    try {
        VkMemoryRequirements req{};
        api.vkGetBufferMemoryRequirements(ctx.device, buffer_, &req);
        const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        std::uint32_t type = 0;
        switch (use) {
            case MemoryUse::Device:
                type = ctx.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
                break;
            case MemoryUse::Upload:
                type = ctx.memory_type(req.memoryTypeBits, host, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
                break;
            case MemoryUse::Readback:
                type = ctx.memory_type(req.memoryTypeBits, host, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
                break;
        }
        VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
        flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        mai.pNext = &flags;
        mai.allocationSize = req.size;
        mai.memoryTypeIndex = type;
        check(api.vkAllocateMemory(ctx.device, &mai, nullptr, &memory_), "vkAllocateMemory");
        check(api.vkBindBufferMemory(ctx.device, buffer_, memory_, 0), "vkBindBufferMemory");
        if (use != MemoryUse::Device)
            check(api.vkMapMemory(ctx.device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
        address_ = device_address(ctx, buffer_);
        // lavapipe's memory is a host mapping: where mmap fails (an address
        // space limit) it still reports success, and the buffer's address and
        // mapping read MAP_FAILED, all ones.
        if (address_ == 0 || address_ == ~VkDeviceAddress(0) || mapped_ == reinterpret_cast<void*>(~std::uintptr_t(0)))
            throw OutOfMemory("Vulkan vkAllocateMemory: " + std::to_string(req.size) +
                              " bytes reported allocated that the driver could not back (out of memory)");
    } catch (...) {
        release();
        throw;
    }
}

Buffer Buffer::adopt(Context::Impl& ctx, VkBuffer buffer, VkDeviceMemory memory, VkDeviceSize bytes, void* mapped) {
    Buffer b;
    b.ctx_ = &ctx;
    b.buffer_ = buffer;
    b.memory_ = memory;
    b.size_ = bytes;
    b.mapped_ = mapped;
    b.address_ = device_address(ctx, buffer);
    return b;
}

Buffer Buffer::borrow(Context::Impl& ctx, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize bytes) {
    Buffer b;
    b.buffer_ = buffer;
    b.offset_ = offset;
    b.size_ = bytes;
    b.address_ = device_address(ctx, buffer);
    return b;
}

void Buffer::release() {
    if (!ctx_) {  // borrowed, or empty
        buffer_ = VK_NULL_HANDLE;
        return;
    }
    auto& api = *ctx_->api;
    if (buffer_) api.vkDestroyBuffer(ctx_->device, buffer_, nullptr);
    if (memory_) api.vkFreeMemory(ctx_->device, memory_, nullptr);  // unmaps implicitly
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    ctx_ = nullptr;
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& o) noexcept
    : ctx_(std::exchange(o.ctx_, nullptr)), offset_(std::exchange(o.offset_, 0)), buffer_(std::exchange(o.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(o.memory_, VK_NULL_HANDLE)), address_(std::exchange(o.address_, 0)),
      size_(std::exchange(o.size_, 0)), mapped_(std::exchange(o.mapped_, nullptr)) {}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        release();
        ctx_ = std::exchange(o.ctx_, nullptr);
        offset_ = std::exchange(o.offset_, 0);
        buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        address_ = std::exchange(o.address_, 0);
        size_ = std::exchange(o.size_, 0);
        mapped_ = std::exchange(o.mapped_, nullptr);
    }
    return *this;
}

}  // namespace vkfuse::vk

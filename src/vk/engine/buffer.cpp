#include "vk/engine/buffer.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

// The buffer's device address; without device addresses, a range of the
// context's handle addresses (Context::Impl::handle_address): the plan's
// graph names buffers by address either way, and no kernel is given one.
VkDeviceAddress device_address(Context::Impl& ctx, VkBuffer buffer, VkDeviceSize bytes) {
    if (!ctx.device_addresses) return ctx.handle_address(bytes);
    VkBufferDeviceAddressInfo bai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    bai.buffer = buffer;
    return ctx.api->vkGetBufferDeviceAddress(ctx.device, &bai);
}

constexpr VkMemoryPropertyFlags kVisible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
constexpr VkMemoryPropertyFlags kCoherent = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

// The memory types a buffer of `use` may take, best first (MemoryUse says
// which): every type with the first preference's flags, then the next's.
std::vector<std::uint32_t> candidate_types(const Context::Impl& ctx, std::uint32_t type_bits, MemoryUse use) {
    std::vector<std::uint32_t> types;
    switch (use) {
        case MemoryUse::Device: types = ctx.memory_types.ranked(type_bits, {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0}); break;
        case MemoryUse::Upload:
            types = ctx.memory_types.ranked(type_bits, {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | kVisible | kCoherent,
                                                        kVisible | kCoherent});
            break;
        case MemoryUse::Readback:
            types = ctx.memory_types.ranked(type_bits, {kVisible | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, kVisible});
            break;
    }
    if (types.empty()) throw Error(ErrorKind::Device, ctx.info.name + ": no suitable memory type");
    return types;
}

[[noreturn]] void unbacked(const std::string& subject, VkDeviceSize bytes) {
    throw OutOfMemory(subject + ": " + std::to_string(bytes) +
                      " bytes reported allocated that the driver could not back (out of memory)");
}

}  // namespace

void check_mapping_backed(const void* mapped, VkDeviceSize bytes, const std::string& subject) {
    if (mapped == reinterpret_cast<const void*>(~std::uintptr_t(0))) unbacked(subject, bytes);
}

VkBufferUsageFlags Buffer::usage(const Context::Impl& ctx) {
    return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |  // a skipping plan's dispatch arguments
           (ctx.device_addresses ? VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT : 0);
}

Buffer::Buffer(Context::Impl& ctx, VkDeviceSize bytes, MemoryUse use) : ctx_(&ctx), size_(bytes) {
    auto& api = *ctx.api;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = bytes < 256 ? 256 : bytes;  // never a zero-sized buffer
    bci.usage = usage(ctx);
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(api.vkCreateBuffer(ctx.device, &bci, nullptr, &buffer_), "vkCreateBuffer");
    try {
        VkMemoryRequirements req{};
        api.vkGetBufferMemoryRequirements(ctx.device, buffer_, &req);
        VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
        flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        mai.pNext = ctx.device_addresses ? &flags : nullptr;
        mai.allocationSize = req.size;
        const std::vector<std::uint32_t> types =
            candidate_types(ctx, ctx.memory_types.visible_bits(req.memoryTypeBits), use);
        // A full heap (a discrete GPU's 256 MiB host-visible window) is not
        // the end: the next type in the preference order takes the buffer.
        VkResult r = VK_ERROR_OUT_OF_DEVICE_MEMORY;
        for (std::uint32_t type : types) {
            mai.memoryTypeIndex = type;
            r = ctx.memory_types.allocate(api, ctx.device, mai, &memory_);
            if (r == VK_SUCCESS) {
                type_ = type;
                allocation_ = req.size;
                if (type != types.front()) ctx.note_fallback(types.front(), type);
                break;
            }
            if (r != VK_ERROR_OUT_OF_DEVICE_MEMORY && r != VK_ERROR_OUT_OF_HOST_MEMORY) break;
        }
        check(r, "vkAllocateMemory");
        check(api.vkBindBufferMemory(ctx.device, buffer_, memory_, 0), "vkBindBufferMemory");
        const VkMemoryPropertyFlags flags_of_type = ctx.memory_types.properties().memoryTypes[type_].propertyFlags;
        coherent_ = (flags_of_type & kCoherent) != 0;
        if (use != MemoryUse::Device) {
            check(api.vkMapMemory(ctx.device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
            check_mapping_backed(mapped_, req.size, "Vulkan vkAllocateMemory");
            if (ctx.memory_types.shadowed(type_)) {
                memory_mapping_ = mapped_;
                shadow_ = std::make_unique<std::byte[]>(bci.size);
                mapped_ = shadow_.get();
            }
        }
        address_ = device_address(ctx, buffer_, bci.size);
        // Unbacked lavapipe memory (check_mapping_backed) reads MAP_FAILED as an address too.
        if (ctx.device_addresses && (address_ == 0 || address_ == ~VkDeviceAddress(0)))
            unbacked("Vulkan vkAllocateMemory", req.size);
    } catch (...) {
        release();
        throw;
    }
}

Buffer Buffer::adopt(Context::Impl& ctx, VkBuffer buffer, VkDeviceMemory memory, std::uint32_t type,
                     VkDeviceSize allocation, VkDeviceSize bytes, void* mapped) {
    Buffer b;
    b.ctx_ = &ctx;
    b.buffer_ = buffer;
    b.memory_ = memory;
    b.type_ = type;
    b.allocation_ = allocation;
    b.size_ = bytes;
    b.mapped_ = mapped;
    b.address_ = device_address(ctx, buffer, bytes);
    return b;
}

Buffer Buffer::borrow(Context::Impl& ctx, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize bytes) {
    Buffer b;
    b.buffer_ = buffer;
    b.offset_ = offset;
    b.size_ = bytes;
    b.address_ = device_address(ctx, buffer, offset + bytes);
    return b;
}

std::uint32_t Buffer::heap() const { return ctx_ ? ctx_->memory_types.heap_of(type_) : 0; }

bool Buffer::device_local() const {
    return ctx_ && (ctx_->memory_types.properties().memoryTypes[type_].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
}

void Buffer::invalidate() const {
    if (!ctx_ || !mapped_ || coherent_) return;
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = memory_;
    range.size = VK_WHOLE_SIZE;
    check(ctx_->api->vkInvalidateMappedMemoryRanges(ctx_->device, 1, &range), "vkInvalidateMappedMemoryRanges");
    if (shadow_) std::memcpy(shadow_.get(), memory_mapping_, size_);
}

void Buffer::release() {
    if (!ctx_) {  // borrowed, or empty
        buffer_ = VK_NULL_HANDLE;
        return;
    }
    auto& api = *ctx_->api;
    if (buffer_) api.vkDestroyBuffer(ctx_->device, buffer_, nullptr);
    ctx_->memory_types.free(api, ctx_->device, memory_, type_, allocation_);  // unmaps implicitly
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    memory_mapping_ = nullptr;
    shadow_.reset();
    ctx_ = nullptr;
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& o) noexcept { *this = std::move(o); }

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
        type_ = std::exchange(o.type_, 0);
        allocation_ = std::exchange(o.allocation_, 0);
        coherent_ = std::exchange(o.coherent_, true);
        memory_mapping_ = std::exchange(o.memory_mapping_, nullptr);
        shadow_ = std::move(o.shadow_);
    }
    return *this;
}

}  // namespace vkfuse::vk

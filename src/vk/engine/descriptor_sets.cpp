#include "vk/engine/descriptor_sets.hpp"

#include <string>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

DescriptorSets::~DescriptorSets() {
    for (VkDescriptorPool p : pools_) ctx_.api->vkDestroyDescriptorPool(ctx_.device, p, nullptr);
}

VkDescriptorSet DescriptorSets::bind(std::span<const DeviceSpan> buffers) {
    if (buffers.size() > ctx_.bound_buffers) throw Error(ErrorKind::Device, "internal: too many kernel buffers");
    auto& api = *ctx_.api;
    if (left_in_pool_ == 0) {
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kSetsPerPool * ctx_.bound_buffers};
        VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pci.maxSets = kSetsPerPool;
        pci.poolSizeCount = 1;
        pci.pPoolSizes = &size;
        VkDescriptorPool pool = VK_NULL_HANDLE;
        check(api.vkCreateDescriptorPool(ctx_.device, &pci, nullptr, &pool), "vkCreateDescriptorPool");
        pools_.push_back(pool);
        left_in_pool_ = kSetsPerPool;
    }
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pools_.back();
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &ctx_.set_layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    check(api.vkAllocateDescriptorSets(ctx_.device, &ai, &set), "vkAllocateDescriptorSets");
    --left_in_pool_;
    const VkDeviceSize range = ctx_.properties.limits.maxStorageBufferRange;
    const VkDeviceSize align = ctx_.properties.limits.minStorageBufferOffsetAlignment;
    VkDescriptorBufferInfo infos[kMaxKernelBuffers]{};
    VkWriteDescriptorSet writes[kMaxKernelBuffers]{};
    for (std::uint32_t b = 0; b < buffers.size(); ++b) {
        const DeviceSpan& s = buffers[b];
        if (s.bytes == 0 || s.bytes > range || s.offset % align != 0)
            throw Error(ErrorKind::Device, "internal: binding " + std::to_string(b) + " of " + std::to_string(s.bytes) +
                                               " bytes at offset " + std::to_string(s.offset) +
                                               " cannot be bound (maxStorageBufferRange " + std::to_string(range) + ")");
        infos[b] = {s.buffer, s.offset, s.bytes};
        writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[b].dstSet = set;
        writes[b].dstBinding = b;
        writes[b].descriptorCount = 1;
        writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[b].pBufferInfo = &infos[b];
    }
    api.vkUpdateDescriptorSets(ctx_.device, std::uint32_t(buffers.size()), writes, 0, nullptr);
    ++written_;
    return set;
}

}  // namespace vkfuse::vk

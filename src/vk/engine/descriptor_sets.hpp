// The descriptor sets of one recorded plan: one set per dispatch of a bound
// kernel, written once at record time and kept as long as the plan (the
// command buffer refers to them). Pools are added as the recording needs them.
#pragma once
#include <span>
#include <vector>

#include "vk/engine/context_impl.hpp"
#include "vk/engine/device_span.hpp"

namespace vkfuse::vk {

class DescriptorSets {
public:
    explicit DescriptorSets(Context::Impl& ctx) : ctx_(ctx) {}
    ~DescriptorSets();
    DescriptorSets(const DescriptorSets&) = delete;
    DescriptorSets& operator=(const DescriptorSets&) = delete;

    // A new set of the context's kernel layout with buffers[i] at binding i
    // (at most kMaxKernelBuffers). Each span must be non-empty and within
    // maxStorageBufferRange.
    VkDescriptorSet bind(std::span<const DeviceSpan> buffers);
    // Sets written so far: one per bound dispatch (none where every kernel took addresses).
    std::uint32_t written() const { return written_; }

private:
    static constexpr std::uint32_t kSetsPerPool = 64;
    Context::Impl& ctx_;
    std::vector<VkDescriptorPool> pools_;
    std::uint32_t left_in_pool_ = 0;
    std::uint32_t written_ = 0;
};

}  // namespace vkfuse::vk

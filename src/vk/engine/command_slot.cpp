#include "vk/engine/command_slot.hpp"

#include <limits>
#include <mutex>
#include <vector>

#include "vk/engine/recorder.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

CommandSlot::CommandSlot(Context::Impl& ctx, std::uint32_t timestamp_queries, bool secondary) : ctx_(ctx) {
    auto& api = *ctx.api;
    try {
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.queueFamilyIndex = ctx.queue_family;
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;  // a measurement records again
        check(api.vkCreateCommandPool(ctx.device, &pci, nullptr, &pool_), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cai.commandPool = pool_;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        check(api.vkAllocateCommandBuffers(ctx.device, &cai, &cmd_), "vkAllocateCommandBuffers");
        if (secondary) {
            cai.level = VK_COMMAND_BUFFER_LEVEL_SECONDARY;
            check(api.vkAllocateCommandBuffers(ctx.device, &cai, &secondary_), "vkAllocateCommandBuffers");
        }
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(api.vkCreateFence(ctx.device, &fci, nullptr, &fence_), "vkCreateFence");
        if (secondary) {  // only what callers embed signals a semaphore (vkfuse::submit)
            VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
            type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
            VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
            sci.pNext = &type;
            check(api.vkCreateSemaphore(ctx.device, &sci, nullptr, &timeline_), "vkCreateSemaphore");
        }
        if (timestamp_queries > 0) {
            VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
            qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
            qci.queryCount = timestamp_queries;
            check(api.vkCreateQueryPool(ctx.device, &qci, nullptr, &queries_), "vkCreateQueryPool");
            query_count_ = timestamp_queries;
        }
    } catch (...) {
        release();
        throw;
    }
}

CommandSlot::~CommandSlot() { release(); }

void CommandSlot::release() {
    auto& api = *ctx_.api;
    // An asynchronous submit (vkfuse::submit) not waited for, or one whose
    // wait failed (device lost, which ends this wait at once).
    if (in_flight_) try {
            wait_for_device();
        } catch (const Error&) {  // a lost device: nothing is pending any more
        }
    if (fence_) api.vkDestroyFence(ctx_.device, fence_, nullptr);
    if (timeline_) api.vkDestroySemaphore(ctx_.device, timeline_, nullptr);
    timeline_ = VK_NULL_HANDLE;
    if (queries_) api.vkDestroyQueryPool(ctx_.device, queries_, nullptr);
    if (pool_) api.vkDestroyCommandPool(ctx_.device, pool_, nullptr);  // frees cmd_ and secondary_
    secondary_ = VK_NULL_HANDLE;
    fence_ = VK_NULL_HANDLE;
    queries_ = VK_NULL_HANDLE;
    query_count_ = 0;
    pool_ = VK_NULL_HANDLE;
    cmd_ = VK_NULL_HANDLE;
    in_flight_ = false;
}

void CommandSlot::record_primary() {
    auto& api = *ctx_.api;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    check(api.vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
    // Embedded plans share the caller's queue and buffers: earlier commands
    // may have written the frames or still read the last fused image. A
    // signalled timeline makes the cycle's writes visible to its waiters.
    memory_barrier(api, cmd_, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    api.vkCmdExecuteCommands(cmd_, 1, &secondary_);
    check(api.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
}

void CommandSlot::submit() {
    if (timeline_) {
        submit_signalling({});
        return;
    }
    auto& api = *ctx_.api;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    check(api.vkResetFences(ctx_.device, 1, &fence_), "vkResetFences");
    {
        std::lock_guard lock(ctx_.queue_mutex);  // submissions of one context may come from several threads
        check(api.vkQueueSubmit(ctx_.queue, 1, &si, fence_), "vkQueueSubmit");
    }
    in_flight_ = true;
}

std::uint64_t CommandSlot::submit_signalling(std::span<const SemaphoreWait> waits) {
    auto& api = *ctx_.api;
    std::vector<VkSemaphore> semaphores;
    std::vector<std::uint64_t> values;
    std::vector<VkPipelineStageFlags> stages;
    for (const SemaphoreWait& w : waits) {
        semaphores.push_back(w.semaphore);
        values.push_back(w.value);
        stages.push_back(w.stages);
    }
    const std::uint64_t signal = timeline_value_ + 1;
    VkTimelineSemaphoreSubmitInfo tsi{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    tsi.waitSemaphoreValueCount = std::uint32_t(values.size());
    tsi.pWaitSemaphoreValues = values.data();
    tsi.signalSemaphoreValueCount = 1;
    tsi.pSignalSemaphoreValues = &signal;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.pNext = &tsi;
    si.waitSemaphoreCount = std::uint32_t(semaphores.size());
    si.pWaitSemaphores = semaphores.data();
    si.pWaitDstStageMask = stages.data();
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    si.signalSemaphoreCount = 1;
    si.pSignalSemaphores = &timeline_;
    {
        std::lock_guard lock(ctx_.queue_mutex);  // submissions of one context may come from several threads
        check(api.vkQueueSubmit(ctx_.queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
    }
    timeline_value_ = signal;
    in_flight_ = true;
    return signal;
}

void CommandSlot::wait_for_device() const {
    const auto forever = std::numeric_limits<std::uint64_t>::max();
    if (timeline_) {
        VkSemaphoreWaitInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
        info.semaphoreCount = 1;
        info.pSemaphores = &timeline_;
        info.pValues = &timeline_value_;
        check(ctx_.api->vkWaitSemaphores(ctx_.device, &info, forever), "vkWaitSemaphores");
    } else {
        check(ctx_.api->vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, forever), "vkWaitForFences");
    }
}

void CommandSlot::wait() {
    wait_for_device();
    in_flight_ = false;
}

std::vector<std::uint64_t> CommandSlot::timestamps(std::uint32_t count) const {
    std::vector<std::uint64_t> ticks(count);
    check(ctx_.api->vkGetQueryPoolResults(ctx_.device, queries_, 0, count, count * sizeof(std::uint64_t), ticks.data(),
                                          sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    // Only the low timestampValidBits bits count, and the counter may wrap
    // between two marks: each tick becomes the previous plus the masked step.
    const std::uint32_t bits = ctx_.timestamp_bits;
    const std::uint64_t mask = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
    for (std::uint32_t i = 1; i < count; ++i) ticks[i] = ticks[i - 1] + ((ticks[i] - ticks[i - 1]) & mask);
    return ticks;
}

}  // namespace vkfuse::vk

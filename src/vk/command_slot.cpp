#include "vk/command_slot.hpp"

#include <limits>
#include <mutex>

namespace vkfuse::vk {

CommandSlot::CommandSlot(Context::Impl& ctx, std::uint32_t timestamp_queries) : ctx_(ctx) {
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
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(api.vkCreateFence(ctx.device, &fci, nullptr, &fence_), "vkCreateFence");
        if (timestamp_queries > 0) {
            VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
            qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
            qci.queryCount = timestamp_queries;
            check(api.vkCreateQueryPool(ctx.device, &qci, nullptr, &queries_), "vkCreateQueryPool");
        }
    } catch (...) {
        release();
        throw;
    }
}

CommandSlot::~CommandSlot() { release(); }

void CommandSlot::release() {
    auto& api = *ctx_.api;
    if (in_flight_) api.vkDeviceWaitIdle(ctx_.device);  // only a submit whose wait failed is still pending
    if (fence_) api.vkDestroyFence(ctx_.device, fence_, nullptr);
    if (queries_) api.vkDestroyQueryPool(ctx_.device, queries_, nullptr);
    if (pool_) api.vkDestroyCommandPool(ctx_.device, pool_, nullptr);  // frees cmd_
    fence_ = VK_NULL_HANDLE;
    queries_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
    cmd_ = VK_NULL_HANDLE;
    in_flight_ = false;
}

void CommandSlot::submit() {
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

void CommandSlot::wait() {
    check(ctx_.api->vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, std::numeric_limits<std::uint64_t>::max()),
          "vkWaitForFences");
    in_flight_ = false;
}

std::vector<std::uint64_t> CommandSlot::timestamps(std::uint32_t count) const {
    std::vector<std::uint64_t> ticks(count);
    check(ctx_.api->vkGetQueryPoolResults(ctx_.device, queries_, 0, count, count * sizeof(std::uint64_t), ticks.data(),
                                          sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    return ticks;
}

}  // namespace vkfuse::vk

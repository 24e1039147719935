#include "vk/timed_commands.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <vector>

#include "vkfuse/error.hpp"

namespace vkfuse::vk {

TimedCommands::TimedCommands(Context::Impl& ctx) : ctx_(ctx) {
    auto& api = *ctx.api;
    try {
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.queueFamilyIndex = ctx.queue_family;
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;  // record() may be called again
        check(api.vkCreateCommandPool(ctx.device, &pci, nullptr, &pool_), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cai.commandPool = pool_;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        check(api.vkAllocateCommandBuffers(ctx.device, &cai, &cmd_), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(api.vkCreateFence(ctx.device, &fci, nullptr, &fence_), "vkCreateFence");
        if (ctx.timestamps) {
            VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
            qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
            qci.queryCount = 2;
            check(api.vkCreateQueryPool(ctx.device, &qci, nullptr, &queries_), "vkCreateQueryPool");
        }
    } catch (...) {
        release();
        throw;
    }
}

TimedCommands::~TimedCommands() { release(); }

void TimedCommands::release() {
    auto& api = *ctx_.api;
    if (fence_) api.vkDestroyFence(ctx_.device, fence_, nullptr);
    if (queries_) api.vkDestroyQueryPool(ctx_.device, queries_, nullptr);
    if (pool_) api.vkDestroyCommandPool(ctx_.device, pool_, nullptr);  // frees cmd_
    fence_ = VK_NULL_HANDLE;
    queries_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
}

void TimedCommands::record(const std::function<void(VkCommandBuffer)>& body) {
    auto& api = *ctx_.api;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    check(api.vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
    if (queries_) {
        api.vkCmdResetQueryPool(cmd_, queries_, 0, 2);
        api.vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    }
    try {
        body(cmd_);
        if (queries_) api.vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
        check(api.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    } catch (...) {
        api.vkResetCommandBuffer(cmd_, 0);  // not left recording: the next record() or run() stays valid
        throw;
    }
}

double TimedCommands::run() {
    auto& api = *ctx_.api;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    check(api.vkResetFences(ctx_.device, 1, &fence_), "vkResetFences");
    const auto start = std::chrono::steady_clock::now();
    {
        std::lock_guard lock(ctx_.queue_mutex);
        check(api.vkQueueSubmit(ctx_.queue, 1, &si, fence_), "vkQueueSubmit");
    }
    check(api.vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, std::numeric_limits<std::uint64_t>::max()),
          "vkWaitForFences");
    const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!queries_) return host;
    std::uint64_t ticks[2] = {};
    check(api.vkGetQueryPoolResults(ctx_.device, queries_, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    return double(ticks[1] - ticks[0]) * ctx_.properties.limits.timestampPeriod * 1e-9;
}

double TimedCommands::median_of(int repeats) {
    if (repeats < 1) throw Error(ErrorKind::InvalidArgument, "timed commands: repeats must be >= 1");
    run();  // warm-up: first touch of pages, pipeline compilation done lazily by some drivers
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) times.push_back(run());
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    return times[times.size() / 2];
}

}  // namespace vkfuse::vk

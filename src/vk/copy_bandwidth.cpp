#include "vk/copy_bandwidth.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <vector>

#include "vk/buffer.hpp"
#include "vkfuse/error.hpp"

namespace vkfuse::vk {
namespace {

// The Vulkan objects of one measurement, released in any case.
struct CopyJob {
    Context::Impl& ctx;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkQueryPool queries = VK_NULL_HANDLE;

    explicit CopyJob(Context::Impl& c) : ctx(c) {
        auto& api = *ctx.api;
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.queueFamilyIndex = ctx.queue_family;
        check(api.vkCreateCommandPool(ctx.device, &pci, nullptr, &pool), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cai.commandPool = pool;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        check(api.vkAllocateCommandBuffers(ctx.device, &cai, &cmd), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(api.vkCreateFence(ctx.device, &fci, nullptr, &fence), "vkCreateFence");
        if (ctx.timestamps) {
            VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
            qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
            qci.queryCount = 2;
            check(api.vkCreateQueryPool(ctx.device, &qci, nullptr, &queries), "vkCreateQueryPool");
        }
    }
    ~CopyJob() {
        auto& api = *ctx.api;
        if (fence) api.vkDestroyFence(ctx.device, fence, nullptr);
        if (queries) api.vkDestroyQueryPool(ctx.device, queries, nullptr);
        if (pool) api.vkDestroyCommandPool(ctx.device, pool, nullptr);
    }
    CopyJob(const CopyJob&) = delete;
    CopyJob& operator=(const CopyJob&) = delete;

    // One command buffer, reused by every repeat: timestamps around one copy.
    void record(const Buffer& src, const Buffer& dst, VkDeviceSize bytes) {
        auto& api = *ctx.api;
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        check(api.vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
        if (queries) {
            api.vkCmdResetQueryPool(cmd, queries, 0, 2);
            api.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries, 0);
        }
        VkBufferCopy region{0, 0, bytes};
        api.vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
        if (queries) api.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, queries, 1);
        check(api.vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    }

    // Seconds the copy took: on the device when it has timestamps, else on the host.
    double submit_and_time() {
        auto& api = *ctx.api;
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd;
        check(api.vkResetFences(ctx.device, 1, &fence), "vkResetFences");
        const auto start = std::chrono::steady_clock::now();
        check(api.vkQueueSubmit(ctx.queue, 1, &si, fence), "vkQueueSubmit");
        check(api.vkWaitForFences(ctx.device, 1, &fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()),
              "vkWaitForFences");
        const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!queries) return host;
        std::uint64_t ticks[2] = {};
        check(api.vkGetQueryPoolResults(ctx.device, queries, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                        VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "vkGetQueryPoolResults");
        return double(ticks[1] - ticks[0]) * ctx.properties.limits.timestampPeriod * 1e-9;
    }
};

}  // namespace

CopyBandwidth measure_copy_bandwidth(Context& context, std::uint64_t bytes, int repeats) {
    if (bytes == 0 || repeats < 1) throw Error(ErrorKind::InvalidArgument, "copy bandwidth: bytes and repeats must be >= 1");
    auto& ctx = context.impl();
    Buffer src(ctx, bytes, MemoryUse::Upload);
    Buffer dst(ctx, bytes, MemoryUse::Device);
    // Touch every source page first, so the first copy does not pay for page faults.
    std::fill_n(static_cast<unsigned char*>(src.mapped()), bytes, static_cast<unsigned char>(1));
    CopyJob job(ctx);
    job.record(src, dst, bytes);
    job.submit_and_time();  // warm-up: first-touch of the destination
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) times.push_back(job.submit_and_time());
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    return {bytes, times[times.size() / 2], job.queries != VK_NULL_HANDLE};
}

}  // namespace vkfuse::vk

#include "vk/engine/timed_commands.hpp"

#include <algorithm>
#include <chrono>
#include <vector>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

TimedCommands::TimedCommands(Context::Impl& ctx) : ctx_(ctx), slot_(ctx, ctx.timestamps() ? 2 : 0) {}

void TimedCommands::record(const std::function<void(VkCommandBuffer)>& body) {
    auto& api = *ctx_.api;
    const VkCommandBuffer cmd = slot_.cmd();
    const VkQueryPool queries = slot_.queries();
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    check(api.vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    if (queries) {
        api.vkCmdResetQueryPool(cmd, queries, 0, 2);
        api.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries, 0);
    }
    try {
        body(cmd);
        if (queries) api.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries, 1);
        check(api.vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    } catch (...) {
        api.vkResetCommandBuffer(cmd, 0);  // not left recording: the next record() or run() stays valid
        throw;
    }
}

double TimedCommands::run() {
    const auto start = std::chrono::steady_clock::now();
    slot_.submit_and_wait();
    const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!device_timed()) return host;
    const auto ticks = slot_.timestamps(2);
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

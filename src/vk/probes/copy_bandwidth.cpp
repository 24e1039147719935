#include "vk/probes/copy_bandwidth.hpp"

#include <algorithm>

#include "vk/engine/buffer.hpp"
#include "vk/engine/timed_commands.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

CopyBandwidth measure_copy_bandwidth(Context& context, std::uint64_t bytes, int repeats) {
    if (bytes == 0 || repeats < 1) throw Error(ErrorKind::InvalidArgument, "copy bandwidth: bytes and repeats must be >= 1");
    auto& ctx = ContextAccess::of(context);
    Buffer src(ctx, bytes, MemoryUse::Upload);
    Buffer dst(ctx, bytes, MemoryUse::Device);
    // Touch every source page first, so the first copy does not pay for page faults.
    std::fill_n(static_cast<unsigned char*>(src.mapped()), bytes, static_cast<unsigned char>(1));
    TimedCommands job(ctx);
    job.record([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, bytes};
        ctx.api->vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
    });
    return {bytes, job.median_of(repeats), job.device_timed()};
}

}  // namespace vkfuse::vk

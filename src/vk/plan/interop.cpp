// vkfuse inside a caller's Vulkan work (vkfuse/vk/interop.hpp): a Context on
// the caller's device, plans reading and writing the caller's buffers, their
// cycle appended to the caller's command buffers or submitted without
// waiting.
#include "vkfuse/vk/interop.hpp"

#include <string>

#include "vk/engine/context_impl.hpp"
#include "vk/plan/plan_impl.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace {

std::size_t frames_bytes(const PlanConfig& c) {
    const std::size_t pixel = c.input == PixelType::U8 ? 1 : 4;
    const std::size_t bytes = std::size_t(c.height) * c.width * c.channels * pixel * c.frames * c.sensors;
    return (bytes + 3) / 4 * 4;  // 8-bit frames are read four samples a word
}

// A caller's range, checked against what the plan reads or writes there.
vk::Buffer borrow(Context::Impl& ctx, const BufferRange& range, std::size_t needed, const std::string& what) {
    const VkDeviceSize alignment = std::max<VkDeviceSize>(16, ctx.properties.limits.minStorageBufferOffsetAlignment);
    if (range.offset % alignment != 0)
        throw Error(ErrorKind::InvalidArgument, what + ": offset " + std::to_string(range.offset) +
                                                    " is not a multiple of " + std::to_string(alignment));
    if (range.size < needed)
        throw Error(ErrorKind::InvalidArgument, what + ": " + std::to_string(range.size) + " bytes, the plan needs " +
                                                    std::to_string(needed));
    // Vulkan cannot say how large a buffer was created; its memory
    // requirement is at least that, so a range past it is surely wrong.
    VkMemoryRequirements req{};
    ctx.api->vkGetBufferMemoryRequirements(ctx.device, range.buffer, &req);
    if (range.offset > req.size || needed > req.size - range.offset)
        throw Error(ErrorKind::InvalidArgument, what + ": " + std::to_string(needed) + " bytes from offset " +
                                                    std::to_string(range.offset) + " run past the buffer's " +
                                                    std::to_string(req.size));
    // Only what the plan reads or writes is bound: a generous range costs nothing.
    return vk::Buffer::borrow(ctx, range.buffer, range.offset, needed);
}

Plan::Impl& embedded(Plan& plan, const char* call) {
    Plan::Impl& im = vk::PlanAccess::of(plan);
    if (!im.embedded)
        throw Error(ErrorKind::InvalidArgument, std::string(call) + ": the plan was not made by vkfuse::make_plan");
    return im;
}

}  // namespace

Context make_context(const CallerDevice& device, const ContextOptions& options) {
    return vk::ContextAccess::adopt(std::make_unique<Context::Impl>(device, options));
}

void Plan::Impl::borrow_buffers(const PlanBuffers& io) {
    if (cfg.skip.policy != SkipPolicy::Off)
        throw Error(ErrorKind::InvalidArgument, "make_plan: skipping needs the host to see every frame; use skip off");
    if (cfg.profile) throw Error(ErrorKind::InvalidArgument, "make_plan: profiling is for plans of their own (Plan)");
    if (io.frames.buffer) device_frames = borrow(ctx, io.frames, frames_bytes(cfg), "make_plan frames buffer");
    if (io.fused.buffer) {
        if (!cfg.want_fused)
            throw Error(ErrorKind::InvalidArgument, "make_plan: a fused buffer was given to a plan without want_fused");
        const std::size_t bytes = std::size_t(cfg.height) * cfg.width * cfg.channels * cfg.sensors * sizeof(float);
        device_fused = borrow(ctx, io.fused, bytes, "make_plan fused buffer");
    }
}

Plan make_plan(Context& context, const PlanConfig& config, const PlanBuffers& buffers) {
    return vk::PlanAccess::make(std::make_unique<Plan::Impl>(
        vk::ContextAccess::of(context), config, config.fuse ? vk::PlanKind::Fuse : vk::PlanKind::Score, &buffers));
}

void upload(Plan& plan, std::span<const FrameView> frames) {
    Plan::Impl& im = embedded(plan, "upload");
    im.finish_pending();
    im.upload_frames(frames);
}

void record(Plan& plan, VkCommandBuffer cmd) {
    Plan::Impl& im = embedded(plan, "record");
    if (!cmd) throw Error(ErrorKind::InvalidArgument, "record: no command buffer");
    im.finish_pending();
    im.check_ready();
    if (im.device_frames.handle()) im.prepare_device_frames();
    const vk::Api& api = *im.ctx.api;
    // The caller's earlier commands wrote the frames (and may still read the
    // last fused image): the cycle waits for them.
    vk::memory_barrier(api, cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    const VkCommandBuffer cycle = im.slot->secondary();
    api.vkCmdExecuteCommands(cmd, 1, &cycle);
    vk::memory_barrier(api, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
}

void finished(Plan& plan) {
    Plan::Impl& im = embedded(plan, "finished");
    im.fused_last_run = true;
    im.complete();
}

std::uint64_t submit(Plan& plan, std::span<const SemaphoreWait> waits) {
    Plan::Impl& im = embedded(plan, "submit");
    im.finish_pending();
    im.check_ready();
    if (im.device_frames.handle()) im.prepare_device_frames();
    const std::uint64_t value = im.slot->submit_signalling(waits);
    ++im.submits;
    im.pending = true;
    im.fused_last_run = true;
    return value;
}

VkSemaphore timeline(const Plan& plan) { return vk::PlanAccess::of(plan).slot->timeline(); }

void wait(Plan& plan) { embedded(plan, "wait").finish_pending(); }

}  // namespace vkfuse

#include "vk/engine/recorder.hpp"

#include <string>

#include "vk/engine/shader_registry.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

Recorder::Recorder(Context::Impl& ctx, VkCommandBuffer cmd, VkQueryPool queries, const std::string& precision,
                   DescriptorSets& sets, bool addressed, bool secondary, std::uint32_t timestamps)
    : ctx_(ctx), cmd_(cmd), queries_(queries), precision_(precision), sets_(sets), addressed_(addressed),
      timestamps_(timestamps) {
    if (addressed && !ctx.device_addresses)
        throw Error(ErrorKind::Device, ctx.info.name + ": a plan beyond maxStorageBufferRange per sensor needs device "
                                                       "addresses (bufferDeviceAddress), which the device lacks");
    VkCommandBufferInheritanceInfo inheritance{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO};
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    if (secondary) {
        bi.flags = VK_COMMAND_BUFFER_USAGE_SIMULTANEOUS_USE_BIT;
        bi.pInheritanceInfo = &inheritance;
    }
    check(ctx.api->vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
    if (queries_) {
        ctx.api->vkCmdResetQueryPool(cmd_, queries_, 0, timestamps_);
        ctx.api->vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    }
    // Frames the host wrote before the submit are read by the first kernels.
    barrier(VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_SHADER_READ_BIT);
}

void memory_barrier(const Api& api, VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags src_access,
                    VkPipelineStageFlags dst, VkAccessFlags dst_access) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = src_access;
    mb.dstAccessMask = dst_access;
    api.vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &mb, 0, nullptr, 0, nullptr);
}

void Recorder::barrier(VkPipelineStageFlags src, VkAccessFlags src_access, VkPipelineStageFlags dst,
                       VkAccessFlags dst_access) {
    memory_barrier(*ctx_.api, cmd_, src, src_access, dst, dst_access);
}

namespace {

// The dispatch against what the kernel's SPIR-V declares (kernel_interface.hpp).
void check_interface(Context::Impl& ctx, const std::string& kernel, std::size_t bindings, const PushConstants& push) {
    const KernelInterface& k = ctx.kernel_interface(kernel);
    if (k.bindings != bindings || k.push_bytes != push.size())
        throw Error(ErrorKind::Device, "internal: " + kernel + " declares " + std::to_string(k.bindings) +
                                           " buffers and " + std::to_string(k.push_bytes) +
                                           " push-constant bytes; the recorder gave " + std::to_string(bindings) +
                                           " and " + std::to_string(push.size()));
    // Field by field: a kernel's block reordered, renamed or retyped, or a
    // C++ field passed out of place, is named here at plan build.
    const auto fields = push.fields();
    for (std::size_t i = 0; i < k.push.size() && i < fields.size(); ++i) {
        const PushMember& want = k.push[i];
        const PushConstants::Field& got = fields[i];
        const bool unnamed_buffer = got.name.empty() && got.type == PushType::Address;
        if ((!unnamed_buffer && got.name != want.name) || got.type != want.type || got.offset != want.offset)
            throw Error(ErrorKind::Device, "internal: " + kernel + "'s push constant " + std::to_string(i) + " is " +
                                               std::string(to_string(want.type)) + " " + want.name + " at byte " +
                                               std::to_string(want.offset) + "; the recorder gave " +
                                               std::string(to_string(got.type)) + " " + std::string(got.name) +
                                               " at byte " + std::to_string(got.offset));
    }
    if (fields.size() != k.push.size())
        throw Error(ErrorKind::Device, "internal: " + kernel + " declares " + std::to_string(k.push.size()) +
                                           " push constants; the recorder gave " + std::to_string(fields.size()));
}

}  // namespace

std::string Recorder::kernel_name(const std::string& shader, bool addressed) const {
    const std::string variant = precision_ + (addressed ? "_addr" : "");
    if (ctx_.filter_arithmetic == FilterArithmetic::Float64 && has_shader(shader + "_f64" + variant))
        return shader + "_f64" + variant;
    return shader + variant;
}

bool Recorder::depends_on_pending(std::span<const DeviceSpan> buffers, std::uint32_t written) const {
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        const DeviceSpan& b = buffers[i];
        const bool writes = written >> i & 1u;
        for (const Access& p : pending_)
            if (b.buffer && b.buffer == p.span.buffer && b.offset < p.span.offset + p.span.bytes &&
                p.span.offset < b.offset + b.bytes && (writes || p.written))
                return true;
    }
    return false;
}

void Recorder::begin_dispatch(const std::string& kernel, std::span<const std::uint32_t> specialization,
                              std::span<const DeviceSpan> buffers, std::uint32_t written) {
    // A barrier only where this dispatch writes a byte that a dispatch since
    // the last barrier reached, or reaches one that such a dispatch wrote
    // (which of its buffers a kernel writes is read from its SPIR-V), so
    // independent dispatches (each level's lap_fuse, passes that only read the
    // same frames) may overlap on the device.
    if (!first_ && depends_on_pending(buffers, written)) {
        barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        pending_.clear();
        ++barriers_;
    }
    for (std::size_t i = 0; i < buffers.size(); ++i)
        if (buffers[i].buffer) pending_.push_back({buffers[i], (written >> i & 1u) != 0});
    ++dispatches_;
    first_ = false;
    ctx_.api->vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, ctx_.pipeline(kernel, specialization));
}

void Recorder::prepare_dispatch(const std::string& shader, std::initializer_list<DeviceSpan> buffers,
                                const PushConstants& scalars, std::span<const std::uint32_t> specialization) {
    // A kernel with more buffers than a stage may bind on this device reaches
    // them by address (the context allows that only with device addresses).
    const bool addressed =
        addressed_ || ctx_.kernel_buffers == KernelBuffers::Addresses || buffers.size() > ctx_.bound_buffers;
    const std::string kernel = kernel_name(shader, addressed);
    // Which buffers it writes: the bound variant's bindings, in the order both take them.
    const std::uint32_t written = ctx_.kernel_interface(kernel_name(shader, false)).written;
    begin_dispatch(kernel, specialization, std::span(buffers.begin(), buffers.size()), written);
    auto& api = *ctx_.api;
    PushConstants push;
    if (addressed) {
        for (const DeviceSpan& b : buffers) push.ptr({}, b.address());
    } else {
        const VkDescriptorSet set = sets_.bind(std::span(buffers.begin(), buffers.size()));
        api.vkCmdBindDescriptorSets(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, ctx_.layout, 0, 1, &set, 0, nullptr);
    }
    push.append(scalars);
    check_interface(ctx_, kernel, addressed ? 0 : buffers.size(), push);
    if (push.size() > 0)
        api.vkCmdPushConstants(cmd_, ctx_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, push.size(), push.data());
}

std::array<std::uint32_t, 3> Recorder::local_size(const std::string& shader) {
    return ctx_.kernel_interface(kernel_name(shader, false)).local_size;
}

void Recorder::dispatch(const std::string& shader, std::initializer_list<DeviceSpan> buffers,
                        const PushConstants& scalars, Work work, std::span<const std::uint32_t> specialization) {
    const auto local = local_size(shader);
    dispatch_groups(shader, buffers, scalars, groups(work.x, local[0]), groups(work.y, local[1]), work.z,
                    specialization);
}

void Recorder::dispatch(const std::string& shader, std::initializer_list<DeviceSpan> buffers,
                        const PushConstants& scalars, LinearWork work, std::span<const std::uint32_t> specialization) {
    const auto local = local_size(shader);
    if (local[1] != 1 || local[2] != 1)
        throw Error(ErrorKind::Device, "internal: " + shader + " is not a 1-D kernel (local size " +
                                           std::to_string(local[0]) + " x " + std::to_string(local[1]) + ")");
    if (work.n == 0) return;
    const Grid grid = grid_1d(work.n, local[0]);
    dispatch_groups(shader, buffers, scalars, grid.x, grid.y, work.z, specialization);
}

void Recorder::dispatch_groups(const std::string& shader, std::initializer_list<DeviceSpan> buffers,
                               const PushConstants& scalars, std::uint32_t gx, std::uint32_t gy, std::uint32_t gz,
                               std::span<const std::uint32_t> specialization) {
    if (gx == 0 || gy == 0 || gz == 0) return;
    prepare_dispatch(shader, buffers, scalars, specialization);
    auto& api = *ctx_.api;
    if (!indirect_) {
        api.vkCmdDispatch(cmd_, gx, gy, gz);
        return;
    }
    if (gz % sensors_ != 0 || per_sensor_.size() >= indirect_capacity_)
        throw Error(ErrorKind::Device, "internal: " + shader + " cannot be recorded per sensor");
    api.vkCmdDispatchIndirect(cmd_, indirect_, per_sensor_.size() * sizeof(VkDispatchIndirectCommand));
    per_sensor_.push_back({gx, gy, gz / sensors_});
}

void Recorder::dispatch_indirect(const std::string& shader, std::initializer_list<DeviceSpan> buffers,
                                 const PushConstants& scalars, VkBuffer args, VkDeviceSize offset) {
    prepare_dispatch(shader, buffers, scalars, {});
    ctx_.api->vkCmdDispatchIndirect(cmd_, args, offset);
}

void Recorder::barrier_for_indirect() {
    barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
                VK_ACCESS_TRANSFER_READ_BIT);
    pending_.clear();
    ++barriers_;
}

void Recorder::compact_sensors(VkBuffer indirect, std::uint32_t capacity, std::uint32_t sensors) {
    indirect_ = indirect;
    indirect_capacity_ = capacity;
    sensors_ = sensors;
}

void Recorder::mark(const std::string& name) {
    if (!queries_) return;
    if (names_.size() + 2 > timestamps_) throw Error(ErrorKind::Device, "internal: too many profiled stages");
    names_.push_back(name);
    ctx_.api->vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, queries_, std::uint32_t(names_.size()));
}

void Recorder::finish() {
    barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
            VK_ACCESS_HOST_READ_BIT);
    check(ctx_.api->vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
}

}  // namespace vkfuse::vk

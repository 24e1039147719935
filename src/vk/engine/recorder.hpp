// Records a plan's dispatches into one command buffer: a barrier before a
// dispatch that writes what an earlier one since the last barrier reached, or
// reaches what such a one wrote (dependent dispatches; independent ones are
// left to overlap) and, when profiling, a timestamp after each stage.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "vk/engine/context_impl.hpp"
#include "vk/engine/descriptor_sets.hpp"
#include "vk/engine/device_span.hpp"
#include "vk/engine/push_constants.hpp"

namespace vkfuse::vk {

class Recorder {
public:
    static constexpr std::uint32_t kMaxTimestamps = 512;

    // queries may be VK_NULL_HANDLE (no profiling). precision is appended to
    // every shader name dispatched ("" or "_fp16": the plan's precision).
    // Kernels get their buffers bound through sets made in `sets`, or, when
    // `addressed`, as device addresses (the kernels' "_addr" variants; also
    // any kernel with more buffers than the context's bound_buffers). A
    // kernel built in both filter arithmetics (shaders/compensated.glsl) runs
    // in the one the context chose: "_f64" before the rest where it is float64.
    // A secondary cmd is begun for simultaneous use outside any render pass
    // (CommandSlot's secondary, executed by its primary and by callers).
    // timestamps: the size of `queries`, what bounds the marks.
    Recorder(Context::Impl& ctx, VkCommandBuffer cmd, VkQueryPool queries, const std::string& precision,
             DescriptorSets& sets, bool addressed, bool secondary = false,
             std::uint32_t timestamps = kMaxTimestamps);

    // What a dispatch covers: x by y invocations, which the kernel's local
    // size (read from its SPIR-V, never restated here) turns into groups, in
    // z layers of groups (planes or sensors).
    struct Work {
        std::uint64_t x = 1, y = 1;
        std::uint32_t z = 1;
    };
    // n invocations of a 1-D kernel (local size (x, 1, 1)), laid out as an
    // (x, y) grid of groups (grid_1d), in z layers.
    struct LinearWork {
        std::uint64_t n = 1;
        std::uint32_t z = 1;
    };

    // Records shader over `work` with `buffers` in the order of its BUFFERS
    // list (shaders/bindings.glsl) and `scalars`, the rest of its
    // push-constant block. Everything the previous dispatches wrote to its buffers is visible
    // to it. specialization: the values of its constant_id 0, 1, ... Nothing
    // is recorded for empty work.
    void dispatch(const std::string& shader, std::initializer_list<DeviceSpan> buffers, const PushConstants& scalars,
                  Work work, std::span<const std::uint32_t> specialization = {});
    void dispatch(const std::string& shader, std::initializer_list<DeviceSpan> buffers, const PushConstants& scalars,
                  LinearWork work, std::span<const std::uint32_t> specialization = {});
    // Exactly gx x gy x gz groups, for kernels whose workgroup is the unit of
    // work (a tile's score, one partial sum, a single decision).
    void dispatch_groups(const std::string& shader, std::initializer_list<DeviceSpan> buffers,
                         const PushConstants& scalars, std::uint32_t gx, std::uint32_t gy, std::uint32_t gz,
                         std::span<const std::uint32_t> specialization = {});
    // The kernel's local size (x, y, z), as its SPIR-V declares it.
    std::array<std::uint32_t, 3> local_size(const std::string& shader);

    // The same with its groups read from `args` at `offset` (a
    // VkDispatchIndirectCommand a kernel wrote: see barrier_for_indirect).
    void dispatch_indirect(const std::string& shader, std::initializer_list<DeviceSpan> buffers,
                           const PushConstants& scalars, VkBuffer args, VkDeviceSize offset);
    // Everything the dispatches so far wrote is visible to the later ones,
    // to indirect dispatches reading their groups, and to transfers.
    void barrier_for_indirect();

    // Sensor-compacting recording (a skipping plan, vk/plan/plan_skip.cpp): from
    // here on every dispatch is recorded as vkCmdDispatchIndirect from the
    // next VkDispatchIndirectCommand of `indirect` (room for `capacity`), and
    // its groups are kept with z divided by `sensors`. Before each submit the
    // host writes z = fused sensors x z per sensor: the fused sensors' data
    // sits in the first slots of every buffer, and each kernel finds its
    // sensor in workgroup z, sensor-major.
    void compact_sensors(VkBuffer indirect, std::uint32_t capacity, std::uint32_t sensors);
    // The groups of each dispatch recorded so far in compacting mode, z per sensor.
    const std::vector<std::array<std::uint32_t, 3>>& sensor_dispatches() const { return per_sensor_; }

    // Closes the stage begun after the previous mark: its GPU time is reported under name.
    void mark(const std::string& name);
    void finish();  // makes shader writes visible to the host and ends the buffer

    const std::vector<std::string>& stage_names() const { return names_; }
    // Dispatches recorded, and the barriers between them (fewer than
    // dispatches - 1 where some were independent).
    std::uint32_t dispatches() const { return dispatches_; }
    std::uint32_t barriers() const { return barriers_; }

private:
    Context::Impl& ctx_;
    VkCommandBuffer cmd_;
    VkQueryPool queries_;
    std::string precision_;  // "" or "_fp16"
    DescriptorSets& sets_;
    bool addressed_;
    std::uint32_t timestamps_;
    bool first_ = true;
    std::vector<std::string> names_;
    VkBuffer indirect_ = VK_NULL_HANDLE;
    std::uint32_t indirect_capacity_ = 0, sensors_ = 1;
    std::vector<std::array<std::uint32_t, 3>> per_sensor_;
    struct Access {
        DeviceSpan span;
        bool written;
    };
    std::vector<Access> pending_;  // what the dispatches since the last barrier reached
    std::uint32_t dispatches_ = 0, barriers_ = 0;

    void barrier(VkPipelineStageFlags src, VkAccessFlags src_access, VkPipelineStageFlags dst,
                 VkAccessFlags dst_access);
    // The embedded variant of shader this recorder dispatches.
    std::string kernel_name(const std::string& shader, bool addressed) const;
    void begin_dispatch(const std::string& kernel, std::span<const std::uint32_t> specialization,
                        std::span<const DeviceSpan> buffers, std::uint32_t written);
    // Everything of a dispatch but the dispatch itself: the barrier it needs,
    // its pipeline, buffers and push constants.
    void prepare_dispatch(const std::string& shader, std::initializer_list<DeviceSpan> buffers,
                          const PushConstants& scalars, std::span<const std::uint32_t> specialization);
    bool depends_on_pending(std::span<const DeviceSpan> buffers, std::uint32_t written) const;
};

// A global memory barrier from (src, src_access) to (dst, dst_access). Its
// first scope is every command submitted earlier to the queue, so one
// recorded in a later submission also orders the earlier ones.
void memory_barrier(const Api& api, VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags src_access,
                    VkPipelineStageFlags dst, VkAccessFlags dst_access);

// Dispatch group count covering n items with groups of size per_group.
inline std::uint32_t groups(std::uint64_t n, std::uint32_t per_group) {
    return std::uint32_t((n + per_group - 1) / per_group);
}

// Groups covering n items of a 1-D kernel, laid out as an (x, y) grid: many
// devices, lavapipe included, allow only 65535 groups along x, fewer than a
// 4096 x 4096 plane needs at 256 per group. The kernel rebuilds its item index
// with linear_index() (common.glsl) and skips the few past n.
struct Grid {
    std::uint32_t x, y;
};
inline Grid grid_1d(std::uint64_t n, std::uint32_t per_group) {
    constexpr std::uint64_t kMaxX = 32768;
    const std::uint64_t total = (n + per_group - 1) / per_group;
    const std::uint64_t x = total < kMaxX ? (total > 0 ? total : 1) : kMaxX;
    return {std::uint32_t(x), std::uint32_t((total + x - 1) / x)};
}

}  // namespace vkfuse::vk

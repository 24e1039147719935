// Plan::Impl: a plan's state (its buffers, backgrounds, scales, skipping,
// cycles in flight), for the plan's own files and the library's access to
// it (vk/plan/interop.cpp). The passes it records are vk/passes/graph.hpp's.
#pragma once
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "vk/engine/buffer.hpp"
#include "vk/engine/command_slot.hpp"
#include "vk/passes/graph.hpp"
#include "vk/plan/plan_skip.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse {

struct Plan::Impl {
    Context::Impl& ctx;
    PlanConfig cfg;
    vk::PlanKind kind;
    // Made by make_plan() (vk/interop.hpp): the cycle is recorded into the
    // slot's secondary command buffer, which callers' command buffers execute.
    bool embedded = false;
    // PlanBuffers ranges of the caller's (borrowed; null handles when unused):
    // the frames read in place of upload's, the fused image written in place
    // of readback's.
    vk::Buffer device_frames, device_fused;
    bool pending = false;   // submit()ted and not yet waited for
    vk::Buffer upload;      // frames as given, host-written each run (none with device_frames)
    // Where upload landed outside device-local memory (a discrete GPU whose
    // host-visible window is full): the kernels' frames, copied from upload
    // at the start of each cycle, so they read device memory, not the bus.
    vk::Buffer staged_frames;
    vk::Buffer background;  // planar float backgrounds, host-written by set_background
    vk::Buffer readback;    // fused HWC images, then the metric partials
    vk::Buffer thresholds;  // Brovey, float32 input: GraphBuilder::brovey_thresholds
    std::vector<vk::Buffer> buffers;
    std::optional<vk::DescriptorSets> sets;  // the bound kernels' descriptors, written by record()
    bool addressed = false;                  // sensors_per_block() 0, or ContextOptions::device_addresses_only
    std::uint32_t dispatches = 0, barriers = 0;  // what record() recorded (Recorder)
    // A skipping plan's detection and compaction (vk/plan/plan_skip.hpp); before
    // `slot`, so the fusion command buffer that reads its indirect arguments
    // is released first.
    std::optional<vk::SkipState> skip;
    // Skipping plans with background_diff: the sensor whose background the
    // device copy holds in each slot (-1: none, or changed since).
    std::vector<int> background_in_slot;
    bool fused_last_run = false;  // the last cycle submitted the fusion command buffer
    bool submitted = false;       // Plan::submit submitted it, and its fence is not yet waited for
    // After the buffers, so it is released (and a pending submit waited out) first.
    std::optional<vk::CommandSlot> slot;
    std::vector<std::string> stage_names;
    std::size_t partials_offset = 0;  // bytes into readback
    std::vector<bool> background_set;
    std::uint64_t submits = 0;
    // PlanConfig::cycles_in_flight 2: the second lane, a plan of the same
    // configuration with buffers and a command buffer of its own; cycles
    // alternate between the two. Null in a one-lane plan and in the second
    // lane itself. The pipeline's state below is kept in the first lane.
    std::unique_ptr<Impl> second_lane;
    std::deque<Impl*> in_flight;  // lanes submitted and not collected, oldest first
    Impl* next_lane = this;       // the lane the next submit takes
    Impl* results = this;         // the lane whose results fused(), metrics(), ... read
    bool collected = false;       // a cycle was collected and no submit came since
    std::vector<Image> fused;  // filled lazily from readback after a run
    std::vector<bool> fused_fresh;
    // Magnitudes (vk/engine/magnitude.hpp). Float32 frames of sensor s went to the
    // device times 2^-exponent[s]; its results are multiplied back.
    std::vector<int> exponent;
    std::vector<int> next_exponent;  // run()'s choice, kept only once every sensor passed
    // Float32 or skipping plans with background_diff: the backgrounds as given (planar),
    // their largest magnitude (float bits), and the exponent the device copy
    // holds them at (nullopt: not written since set_background).
    std::vector<float> background_host;
    std::vector<std::uint32_t> background_max;
    std::vector<std::optional<int>> background_exponent;

    // io: make_plan()'s buffers (an embedded plan), or null.
    Impl(Context::Impl& context, const PlanConfig& config, vk::PlanKind plan_kind, const PlanBuffers* io = nullptr);
    // A plan of an internal kind (BackgroundMean): what Plan's public
    // constructor cannot make.
    static Plan make(Context& context, const PlanConfig& config, vk::PlanKind plan_kind);
    // The first lane of a plan, with its second lane where
    // config.cycles_in_flight asks for one.
    static std::unique_ptr<Impl> with_lanes(Context::Impl& context, const PlanConfig& config, vk::PlanKind plan_kind);
    // This lane and the second, where there is one.
    std::vector<Impl*> lanes() { return second_lane ? std::vector<Impl*>{this, second_lane.get()} : std::vector<Impl*>{this}; }
    // The lane whose results call (e.g. "fused()") reads: refused before any
    // cycle was collected, and after a submit() since.
    Impl& readable(const char* call) const;
    // Waits for the device to finish the cycle submitted in this lane (the
    // cycle stays to be collected): before the host rewrites what it reads.
    void wait_device();
    // Plan::set_background on this lane (checked by the caller).
    void set_background(int sensor, const FrameView& background);
    bool brovey() const { return kind == vk::PlanKind::Fuse && cfg.fusion.method == Method::Brovey; }
    // Where sensor's results lie in the read-back buffer: its slot in the last run.
    std::size_t result_slot(int sensor) const { return skip ? std::size_t(*skip->slot(sensor)) : std::size_t(sensor); }
    bool skipped(int sensor) const { return skip && !skip->slot(sensor); }
    // Skipping: the fused sensors' frames and backgrounds into slots 0..F-1.
    void compact(std::span<const FrameView> frames, const std::vector<int>& fused_sensors);
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    // Sensors per recorded block: every sensor where the plan's buffers fit
    // one binding, 0 where the kernels must use device addresses (in one
    // block); and the blocks that makes.
    std::uint32_t sensors_per_block() const;
    std::uint32_t blocks() const;
    void record();
    // Records the pass chain of sensors from .. from + count - 1 (a block,
    // vk/plan/sensor_blocks.hpp), on the intermediates from index reuse_from of
    // `buffers` on where given (a block after the first).
    void record_sensors(vk::Recorder& rec, std::uint32_t from, std::uint32_t count,
                        std::optional<std::size_t> reuse_from);
    // make_plan()'s buffers, checked against the plan (vk/plan/interop.cpp).
    void borrow_buffers(const PlanBuffers& io);
    // Throws unless every background and skip reference the plan needs is set.
    void check_ready() const;
    // Host frames into the upload buffer, checked (count, shapes, values).
    void upload_frames(std::span<const FrameView> frames);
    // A cycle of frames read from device_frames is about to start: they are
    // taken unscaled, so a float32 plan's backgrounds go to the device as
    // given, and every result is read at the frames' own scale.
    void prepare_device_frames();
    // A cycle ended: its results are what fused() and metrics() read.
    void complete();
    // Results are read while an asynchronous submit is pending: refused, as
    // they would be the previous cycle's, or half written.
    void check_not_pending(const char* call) const;
    // An asynchronous submit still pending is waited for.
    void finish_pending();
};

namespace vk {

// The library's access to a Plan's internals (vk/plan/interop.cpp).
struct PlanAccess {
    static Plan::Impl& of(Plan& plan) { return *plan.impl_; }
    static const Plan::Impl& of(const Plan& plan) { return *plan.impl_; }
    static Plan make(std::unique_ptr<Plan::Impl> impl) { return Plan(std::move(impl)); }
};

}  // namespace vk

}  // namespace vkfuse

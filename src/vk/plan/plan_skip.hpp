// What a skipping plan (PlanConfig::skip) adds to a plan. Under
// SkipPolicy::Idle the device decides, and a cycle is one submit
// (vk/plan/skip_on_device.cpp):
//
//   upload (S sensors) -> change_detect -> skip_decide (one workgroup):
//        fused sensors -> slots 0..F-1, indirect arguments (z = F x its z per
//        sensor), which slots' frames and backgrounds move
//   -> scores and slots copied out -> skip_gather: frames of slots g..F-1
//        through a scratch buffer, changed slots' backgrounds
//   -> the fusion, recorded once with indirect dispatches (none run when F = 0)
//
// Where the host must decide (Static keeps results the host holds, Tiles
// chooses regions on the host; and frames whose sensors do not start on
// word boundaries, which the gathers cannot move), two submits:
//
//   upload (S sensors) -> change_detect -> scores read back       1st submit
//   host: sensors with a tile over the threshold are "fused", the rest idle;
//         the fused sensors' frames (and backgrounds) move to slots 0..F-1;
//         every dispatch's z becomes F x its z per sensor (indirect arguments)
//   fusion command buffer, recorded once with indirect dispatches  2nd submit, only when F > 0
//
// An idle sensor's result is its fused reference (fused once, on the host, in
// double precision) and that image's metrics, computed once. Under
// SkipPolicy::Static the frames of each sensor's last fused cycle are kept on
// the device, and its result on the host (taken from the read-back buffer at
// the start of the next run): a sensor whose frames still match them reuses it.
// Under SkipPolicy::Tiles a fused sensor may be fused only in part
// (vk/passes/plan_sparse.hpp).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "vk/engine/buffer.hpp"
#include "vk/engine/command_slot.hpp"
#include "vk/engine/descriptor_sets.hpp"
#include "vk/passes/plan_sparse.hpp"
#include "vk/engine/recorder.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::vk {

// Whether a skipping plan of cfg decides on the device, in one submit a cycle.
bool skip_decides_on_device(const PlanConfig& cfg);

class SkipState {
public:
    // Indirect dispatches a plan may hold: the fusion's (kFusionDispatches),
    // then the device decision's three gathers (12 bytes apiece).
    static constexpr std::uint32_t kMaxDispatches = 1024;
    static constexpr std::uint32_t kFusionDispatches = kMaxDispatches - 3;

    SkipState(Context::Impl& ctx, const PlanConfig& cfg, const Buffer& upload, bool addressed);
    SkipState(const SkipState&) = delete;
    SkipState& operator=(const SkipState&) = delete;

    VkBuffer indirect() const { return indirect_.handle(); }
    // The fusion's indirect dispatches, each with z per sensor (after its recording).
    void set_dispatches(std::vector<std::array<std::uint32_t, 3>> per_sensor);

    // Decided on the device (skip_decides_on_device): record_on_device
    // records the detection, the decision and the gathers into the plan's
    // command buffer, before the fusion; `frames` are the plan's frames (the
    // fused ones are moved into slots 0..F-1 there), `background_slots` the
    // per-slot backgrounds the metrics read (empty without background_diff).
    bool on_device() const { return on_device_; }
    void record_on_device(Recorder& rec, VkCommandBuffer cmd, const DeviceSpan& frames,
                          const DeviceSpan& background_slots);
    // A sensor's background changed: planar, H*W*C floats, as the metrics take it.
    void set_background(int sensor, const float* planar);
    // After the cycle's fence: the device's decision becomes the outcomes and
    // slots; returns the sensors fused.
    int read_decision();

    void set_reference(int sensor, const SkipReference& reference);
    bool has_reference(int sensor) const { return reference_set_.at(std::size_t(sensor)); }

    // Decided on the host: runs the detection over the uploaded frames and
    // decides who is fused; returns the fused sensors in slot order and
    // writes the indirect arguments for that many.
    std::vector<int> detect();

    const SkipOutcome& outcome(int sensor) const { return outcomes_.at(std::size_t(sensor)); }
    // Slot of sensor's results in the last run, nullopt when it was skipped.
    std::optional<int> slot(int sensor) const { return slot_.at(std::size_t(sensor)); }
    // A skipped sensor's result: the fused reference, or the kept result.
    const Image& skipped_image(int sensor) const;
    // Its metrics: the kept ones, or those of the fused reference (with
    // background_diff against `background` when given), computed on first
    // use after the reference or the background changed.
    Metrics skipped_metrics(int sensor, const float* planar_background);
    void background_changed(int sensor);

    bool statics() const { return reuses_still_presses(cfg_.skip.policy); }
    // Tiles on a plan that can fuse sparsely: its region records; else null.
    SparseRegions* sparse() { return sparse_ ? &*sparse_ : nullptr; }
    // The fused sensors' frames become what their next cycles are compared with.
    void keep_frames(std::span<const FrameView> frames, const std::vector<int>& fused_sensors);
    // Whether sensor's result of the last run is still to be kept; keep it.
    bool result_pending(int sensor) const { return pending_.at(std::size_t(sensor)); }
    void keep_result(int sensor, const Image* fused, const Metrics& metrics);

private:
    Context::Impl& ctx_;
    PlanConfig cfg_;
    bool on_device_;
    std::uint32_t tiles_x_, tiles_y_;
    Buffer means_;      // S*K*C planes, float32
    Buffer inv_noise_;  // S*K*tiles: 1 / tile noise
    Buffer scores_;     // S*tiles, device memory (the kernel's atomicMax)
    Buffer previous_;   // Static: S*K frames of each sensor's last fused cycle, 8-bit
    Buffer statics_;    // Static: S*tiles scores against them, device memory
    Buffer scores_readback_;  // scores_ then statics_ (or the slots decided on the device), copied out
    Buffer indirect_;   // VkDispatchIndirectCommand per indirect dispatch
    // Decided on the device (shaders/skip_decision.glsl has their layout):
    Buffer host_args_;    // the dispatches' groups and the backgrounds' versions
    Buffer decision_;     // slots, gathers and the backgrounds each slot holds
    Buffer scratch_;      // the moved sensors' frames on their way
    Buffer backgrounds_;  // every sensor's background, planar float32
    std::vector<std::uint32_t> background_version_;
    std::optional<SparseRegions> sparse_;
    std::optional<DescriptorSets> sets_;
    std::optional<CommandSlot> detect_;
    std::vector<std::array<std::uint32_t, 3>> dispatches_;
    std::vector<bool> reference_set_;
    std::vector<Image> fused_;
    std::vector<std::optional<Metrics>> idle_metrics_;
    std::vector<SkipOutcome> outcomes_;
    std::vector<std::optional<int>> slot_;
    std::vector<bool> pending_, kept_;  // Static: result to keep at the next run; kept
    std::vector<Image> kept_image_;
    std::vector<Metrics> kept_metrics_;

    static constexpr std::uint32_t kNotFused = 0xffffffffu;  // a slot in `decision_` (skip_decision.glsl)

    void make_device_buffers();
    void record(const Buffer& upload, bool addressed);
    void record_detection(Recorder& rec, VkCommandBuffer cmd, const DeviceSpan& frames);
    // The outcomes and slots from the scores (and statics) read back, the
    // slots given where the device chose them; returns the fused sensors.
    std::vector<int> decide(const float* scores, const float* still, const std::uint32_t* device_slots);
};

}  // namespace vkfuse::vk

// What a skipping plan (PlanConfig::skip) adds to a plan. Each run:
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
// (vk/plan_sparse.hpp).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "vk/buffer.hpp"
#include "vk/command_slot.hpp"
#include "vk/descriptor_sets.hpp"
#include "vk/plan_sparse.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::vk {

class SkipState {
public:
    // Dispatches the fusion command buffer may hold: indirect arguments are
    // written for each (12 bytes apiece).
    static constexpr std::uint32_t kMaxDispatches = 1024;

    SkipState(Context::Impl& ctx, const PlanConfig& cfg, const Buffer& upload, bool addressed);
    SkipState(const SkipState&) = delete;
    SkipState& operator=(const SkipState&) = delete;

    VkBuffer indirect() const { return indirect_.handle(); }
    void set_dispatches(std::vector<std::array<std::uint32_t, 3>> per_sensor) { dispatches_ = std::move(per_sensor); }

    void set_reference(int sensor, const SkipReference& reference);
    bool has_reference(int sensor) const { return reference_set_.at(std::size_t(sensor)); }

    // Runs the detection over the uploaded frames and decides who is fused;
    // returns the fused sensors in slot order and writes the indirect
    // arguments for that many.
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
    std::uint32_t tiles_x_, tiles_y_;
    Buffer means_;      // S*K*C planes, float32
    Buffer inv_noise_;  // S*K*tiles: 1 / tile noise
    Buffer scores_;     // S*tiles, device memory (the kernel's atomicMax)
    Buffer previous_;   // Static: S*K frames of each sensor's last fused cycle, 8-bit
    Buffer statics_;    // Static: S*tiles scores against them, device memory
    Buffer scores_readback_;  // scores_ then statics_, copied out after the kernel
    Buffer indirect_;   // VkDispatchIndirectCommand per fusion dispatch
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

    void record(const Buffer& upload, bool addressed);
};

}  // namespace vkfuse::vk

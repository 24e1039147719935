// What a skipping plan (PlanConfig::skip) adds to a plan. Each run:
//
//   upload (S sensors) -> change_detect -> scores read back       1st submit
//   host: sensors with a tile over the threshold are "fused", the rest idle;
//         the fused sensors' frames (and backgrounds) move to slots 0..F-1;
//         every dispatch's z becomes F x its z per sensor (indirect arguments)
//   fusion command buffer, recorded once with indirect dispatches  2nd submit, only when F > 0
//
// An idle sensor's result is its fused reference (fused once, on the host, in
// double precision) and that image's metrics, computed once.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "vk/buffer.hpp"
#include "vk/command_slot.hpp"
#include "vk/descriptor_sets.hpp"
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
    // Slot of sensor's results in the last run, nullopt when it was idle.
    std::optional<int> slot(int sensor) const { return slot_.at(std::size_t(sensor)); }
    const Image& fused_reference(int sensor) const { return fused_.at(std::size_t(sensor)); }
    // The cached metrics of the fused reference (with background_diff
    // against `background` when given): computed on first use after the
    // reference or the background changed.
    Metrics idle_metrics(int sensor, const float* planar_background);
    void background_changed(int sensor) { idle_metrics_.at(std::size_t(sensor)).reset(); }

private:
    Context::Impl& ctx_;
    PlanConfig cfg_;
    std::uint32_t tiles_x_, tiles_y_;
    Buffer means_;      // S*K*C planes, float32
    Buffer inv_noise_;  // S*K*tiles: 1 / tile noise
    Buffer scores_;     // S*tiles, read back
    Buffer indirect_;   // VkDispatchIndirectCommand per fusion dispatch
    std::optional<DescriptorSets> sets_;
    std::optional<CommandSlot> detect_;
    std::vector<std::array<std::uint32_t, 3>> dispatches_;
    std::vector<bool> reference_set_;
    std::vector<Image> fused_;
    std::vector<std::optional<Metrics>> idle_metrics_;
    std::vector<SkipOutcome> outcomes_;
    std::vector<std::optional<int>> slot_;

    void record(const Buffer& upload, bool addressed);
};

}  // namespace vkfuse::vk

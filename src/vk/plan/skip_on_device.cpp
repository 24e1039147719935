// A skipping plan that decides on the device (vk/plan/plan_skip.hpp): detection,
// decision and compaction recorded before the fusion, one submit a cycle.
// host_args_ and decision_ are laid out as shaders/skip_decision.glsl says.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "vk/engine/kernel_codes.hpp"
#include "vk/plan/plan_skip.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

// shaders/skip_decision.glsl's layout for S sensors, in 32-bit words.
struct DecisionLayout {
    std::size_t S;
    static constexpr std::size_t kDispatchCount = 0;
    static std::size_t gather(std::size_t i) { return 1 + 3 * i; }
    std::size_t version(std::size_t s) const { return 10 + s; }
    std::size_t fusion(std::size_t d) const { return 10 + S + 3 * d; }
    std::size_t host_words() const { return fusion(SkipState::kFusionDispatches); }
    std::size_t decision_words() const { return 5 * S + 3; }
};

// skip_gather.comp's modes, in the order of their indirect commands.
enum class Gather : std::uint32_t { FramesOut, FramesIn, Backgrounds };
constexpr std::uint32_t kGatherInvocationWords = VKFUSE_GATHER_WORDS;

// The largest float not above t: a float score v is <= t exactly when it is
// <= this, so the device's float comparison decides as the host's in double.
float threshold_below(double t) {
    float f = float(t);
    if (double(f) > t) f = std::nextafter(f, -INFINITY);
    return f;
}

std::uint64_t sensor_frame_bytes(const PlanConfig& c) {  // K 8-bit frames
    return std::uint64_t(c.height) * std::uint64_t(c.width) * std::uint64_t(c.channels) * std::uint64_t(c.frames);
}

}  // namespace

// Static keeps results on the host and Tiles chooses regions there; the
// gathers move whole words, so every sensor's frames must start on one.
bool skip_decides_on_device(const PlanConfig& cfg) {
    return cfg.skip.policy == SkipPolicy::Idle && sensor_frame_bytes(cfg) % 4 == 0;
}

void SkipState::make_device_buffers() {
    const std::size_t S = std::size_t(cfg_.sensors);
    const DecisionLayout at{S};
    host_args_ = Buffer(ctx_, at.host_words() * 4, MemoryUse::Upload);
    auto* host = static_cast<std::uint32_t*>(host_args_.mapped());
    std::fill_n(host, at.host_words(), 0u);
    decision_ = Buffer(ctx_, at.decision_words() * 4, MemoryUse::Upload);
    // No slot holds a background yet.
    std::fill_n(static_cast<std::uint32_t*>(decision_.mapped()), at.decision_words(), kNotFused);
    // Fused sensors move from slot 1 on at most.
    const std::uint64_t bytes = sensor_frame_bytes(cfg_);
    scratch_ = Buffer(ctx_, std::max<std::size_t>(S - 1, 1) * bytes, MemoryUse::Device);
    const std::uint64_t samples = bytes / std::uint64_t(cfg_.frames);
    if (cfg_.metrics.has(Metric::BackgroundDiff)) backgrounds_ = Buffer(ctx_, S * samples * 4, MemoryUse::Upload);
    background_version_.assign(S, 0);
    // Each gather's groups for one slot; the decision multiplies z.
    const std::uint32_t group_words = ctx_.kernel_interface("skip_gather").local_size[0] * kGatherInvocationWords;
    const Grid frames = grid_1d(bytes / 4, group_words), planes = grid_1d(samples, group_words);
    for (const auto& [mode, grid] : {std::pair{Gather::FramesOut, frames}, std::pair{Gather::FramesIn, frames},
                                    std::pair{Gather::Backgrounds, planes}}) {
        std::uint32_t* g = host + DecisionLayout::gather(std::size_t(mode));
        g[0] = grid.x;
        g[1] = grid.y;
        g[2] = 1;
    }
}

void SkipState::set_dispatches(std::vector<std::array<std::uint32_t, 3>> per_sensor) {
    dispatches_ = std::move(per_sensor);
    if (!on_device_) return;
    const DecisionLayout at{std::size_t(cfg_.sensors)};
    auto* host = static_cast<std::uint32_t*>(host_args_.mapped());
    host[DecisionLayout::kDispatchCount] = std::uint32_t(dispatches_.size());
    for (std::size_t d = 0; d < dispatches_.size(); ++d) std::copy_n(dispatches_[d].data(), 3, host + at.fusion(d));
}

void SkipState::record_on_device(Recorder& rec, VkCommandBuffer cmd, const DeviceSpan& frames,
                                 const DeviceSpan& background_slots) {
    const Api& api = *ctx_.api;
    const auto S = std::uint32_t(cfg_.sensors);
    record_detection(rec, cmd, frames);
    rec.dispatch_groups("skip_decide", {scores_.span(), host_args_.span(), decision_.span(), indirect_.span()},
                 PushConstants()
                     .u32("sensors", S)
                     .u32("tiles", tiles_x_ * tiles_y_)
                     .u32("gather_args", kFusionDispatches)
                     .u32("backgrounds", background_slots.buffer != VK_NULL_HANDLE)
                     .f32("threshold", threshold_below(cfg_.skip.threshold)),
                 1, 1, 1);
    rec.barrier_for_indirect();
    // The scores and the slots, for the outcomes the host reports.
    const VkBufferCopy to_scores{0, 0, scores_.size()}, to_slots{0, scores_.size(), VkDeviceSize(S) * 4};
    api.vkCmdCopyBuffer(cmd, scores_.handle(), scores_readback_.handle(), 1, &to_scores);
    api.vkCmdCopyBuffer(cmd, decision_.handle(), scores_readback_.handle(), 1, &to_slots);
    memory_barrier(api, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                   VK_ACCESS_HOST_READ_BIT);
    rec.mark("change_detect");
    const auto gather_at = [](Gather mode) {
        return VkDeviceSize(kFusionDispatches + std::uint32_t(mode)) * sizeof(VkDispatchIndirectCommand);
    };
    const auto frame_words = std::uint32_t(sensor_frame_bytes(cfg_) / 4);
    rec.dispatch_indirect(
        "skip_gather", {frames, scratch_.span(), decision_.span()},
        PushConstants().u32("sensors", S).u32("words", frame_words).u32("mode", std::uint32_t(Gather::FramesOut)),
        indirect_.handle(), gather_at(Gather::FramesOut));
    rec.dispatch_indirect(
        "skip_gather", {scratch_.span(), frames, decision_.span()},
        PushConstants().u32("sensors", S).u32("words", frame_words).u32("mode", std::uint32_t(Gather::FramesIn)),
        indirect_.handle(), gather_at(Gather::FramesIn));
    if (background_slots.buffer)
        rec.dispatch_indirect("skip_gather", {backgrounds_.span(), background_slots, decision_.span()},
                              PushConstants()
                                  .u32("sensors", S)
                                  .u32("words", frame_words * 4 / std::uint32_t(cfg_.frames))
                                  .u32("mode", std::uint32_t(Gather::Backgrounds)),
                              indirect_.handle(), gather_at(Gather::Backgrounds));
    rec.mark("compact");
}

void SkipState::set_background(int sensor, const float* planar) {
    if (!on_device_ || !backgrounds_.handle()) return;
    const std::size_t samples = sensor_frame_bytes(cfg_) / std::size_t(cfg_.frames), s = std::size_t(sensor);
    std::memcpy(static_cast<float*>(backgrounds_.mapped()) + s * samples, planar, samples * sizeof(float));
    // A slot holding this sensor's background copies it again at its next fused cycle.
    static_cast<std::uint32_t*>(host_args_.mapped())[DecisionLayout{std::size_t(cfg_.sensors)}.version(s)] =
        ++background_version_[s];
}

int SkipState::read_decision() {
    scores_readback_.invalidate();
    const auto* bytes = static_cast<const std::uint8_t*>(scores_readback_.mapped());
    const auto* slots = reinterpret_cast<const std::uint32_t*>(bytes + scores_.size());
    return int(decide(reinterpret_cast<const float*>(bytes), nullptr, slots).size());
}

}  // namespace vkfuse::vk

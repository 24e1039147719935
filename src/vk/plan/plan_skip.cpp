// A skipping plan's change detection and sensor compaction (vk/plan/plan_skip.hpp).
#include "vk/plan/plan_skip.hpp"

#include <cstring>
#include <string>

#include "vk/plan/plan_impl.hpp"
#include "vk/engine/recorder.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::vk {

SkipState::SkipState(Context::Impl& ctx, const PlanConfig& cfg, const Buffer& upload, bool addressed)
    : ctx_(ctx),
      cfg_(cfg),
      on_device_(skip_decides_on_device(cfg)),
      tiles_x_(std::uint32_t(skip_tiles_x(cfg.width))),
      tiles_y_(std::uint32_t(skip_tiles_y(cfg.height))) {
    const std::size_t S = std::size_t(cfg.sensors), K = std::size_t(cfg.frames), tiles = tiles_x_ * tiles_y_;
    const std::size_t samples = S * K * std::size_t(cfg.channels) * std::size_t(cfg.height) * std::size_t(cfg.width);
    means_ = Buffer(ctx, (samples * 2 + 3) / 4 * 4, MemoryUse::Upload);
    inv_noise_ = Buffer(ctx, S * K * tiles * 4, MemoryUse::Upload);
    // The kernel's atomicMax works on device memory; the scores come back by copy.
    scores_ = Buffer(ctx, S * tiles * 4, MemoryUse::Device);
    if (statics()) {
        previous_ = Buffer(ctx, (samples + 3) / 4 * 4, MemoryUse::Upload);
        statics_ = Buffer(ctx, S * tiles * 4, MemoryUse::Device);
    }
    // Scores, then statics' scores or the slots decided on the device.
    scores_readback_ = Buffer(ctx, S * tiles * 4 + (statics() ? S * tiles * 4 : on_device_ ? S * 4 : 0), MemoryUse::Readback);
    // Written by the host, or by skip_decide.comp.
    indirect_ = Buffer(ctx, kMaxDispatches * sizeof(VkDispatchIndirectCommand),
                       on_device_ ? MemoryUse::Device : MemoryUse::Upload);
    if (sparse_capable(cfg)) sparse_.emplace(ctx, cfg);
    reference_set_.assign(S, false);
    fused_.resize(S);
    idle_metrics_.resize(S);
    outcomes_.resize(S);
    slot_.resize(S);
    pending_.assign(S, false);
    kept_.assign(S, false);
    kept_image_.resize(S);
    kept_metrics_.resize(S);
    if (on_device_)
        make_device_buffers();
    else
        record(upload, addressed);
}

void SkipState::record_detection(Recorder& rec, VkCommandBuffer cmd, const DeviceSpan& frames) {
    const Api& api = *ctx_.api;
    // The kernel's atomicMax starts from 0.
    api.vkCmdFillBuffer(cmd, scores_.handle(), 0, VK_WHOLE_SIZE, 0);
    if (statics()) api.vkCmdFillBuffer(cmd, statics_.handle(), 0, VK_WHOLE_SIZE, 0);
    memory_barrier(api, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    // Without Static the kernel never reads `previous` nor writes `statics`:
    // the frames and the scores stand in for their bindings.
    const DeviceSpan previous = statics() ? previous_.span() : frames;
    const DeviceSpan static_scores = statics() ? statics_.span() : scores_.span();
    rec.dispatch_groups("change_detect", {frames, means_.span(), inv_noise_.span(), scores_.span(), previous, static_scores},
                 PushConstants()
                     .u32("width", std::uint32_t(cfg_.width))
                     .u32("height", std::uint32_t(cfg_.height))
                     .u32("channels", std::uint32_t(cfg_.channels))
                     .u32("frames", std::uint32_t(cfg_.frames))
                     .u32("aligned", cfg_.width % 4 == 0)
                     .u32("previous", statics()),
                 tiles_x_, tiles_y_, std::uint32_t(cfg_.sensors));
}

void SkipState::record(const Buffer& upload, bool addressed) {
    sets_.emplace(ctx_);
    detect_.emplace(ctx_, 0);
    Recorder rec(ctx_, detect_->cmd(), VK_NULL_HANDLE, "", *sets_, addressed);
    const Api& api = *ctx_.api;
    const VkCommandBuffer cmd = detect_->cmd();
    record_detection(rec, cmd, upload.span());
    const VkDeviceSize score_bytes = scores_.size();
    memory_barrier(api, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferCopy to_scores{0, 0, score_bytes}, to_statics{0, score_bytes, score_bytes};
    api.vkCmdCopyBuffer(cmd, scores_.handle(), scores_readback_.handle(), 1, &to_scores);
    if (statics()) api.vkCmdCopyBuffer(cmd, statics_.handle(), scores_readback_.handle(), 1, &to_statics);
    memory_barrier(api, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                   VK_ACCESS_HOST_READ_BIT);
    rec.finish();
}

void SkipState::set_reference(int sensor, const SkipReference& reference) {
    const std::string what = "skip reference of sensor " + std::to_string(sensor);
    check_skip_reference(reference, cfg_.height, cfg_.width, cfg_.channels, cfg_.frames, what);
    const std::size_t K = std::size_t(cfg_.frames), C = std::size_t(cfg_.channels);
    const std::size_t pixels = std::size_t(cfg_.height) * std::size_t(cfg_.width), tiles = tiles_x_ * tiles_y_;
    // In the frames' own order (HWC, frame after frame), as 16-bit fixed point.
    auto* means = static_cast<std::uint16_t*>(means_.mapped()) + std::size_t(sensor) * K * C * pixels;
    for (std::size_t k = 0; k < K; ++k)
        for (std::size_t i = 0; i < C * pixels; ++i) means[k * C * pixels + i] = skip_mean_fixed(reference.mean[k].data[i]);
    // Distances reach the kernel in fixed-point steps.
    const std::vector<float> noise = tile_noise(reference);
    float* inv = static_cast<float*>(inv_noise_.mapped()) + std::size_t(sensor) * K * tiles;
    for (std::size_t i = 0; i < noise.size(); ++i) inv[i] = float(1.0 / double(noise[i]));  // steps, as the means
    std::vector<ImageD> means_d;
    for (const Image& m : reference.mean) means_d.push_back(convert<double>(m));
    fused_[std::size_t(sensor)] = convert<float>(fuse_reference(means_d, cfg_.fusion));
    if (sparse_) sparse_->set_background(sensor, fused_[std::size_t(sensor)]);
    background_changed(sensor);
    reference_set_[std::size_t(sensor)] = true;
}

void SkipState::background_changed(int sensor) {
    const std::size_t s = std::size_t(sensor);
    idle_metrics_.at(s).reset();
    pending_.at(s) = false;  // a kept result's metrics would be against the old background
    kept_.at(s) = false;
}

void SkipState::keep_frames(std::span<const FrameView> frames, const std::vector<int>& fused_sensors) {
    if (!statics()) return;
    const std::size_t K = std::size_t(cfg_.frames);
    const std::size_t n = std::size_t(cfg_.height) * std::size_t(cfg_.width) * std::size_t(cfg_.channels);
    auto* dst = static_cast<std::uint8_t*>(previous_.mapped());
    for (int s : fused_sensors) {
        for (std::size_t k = 0; k < K; ++k)
            std::memcpy(dst + (std::size_t(s) * K + k) * n, frames[std::size_t(s) * K + k].data, n);
        pending_[std::size_t(s)] = true;
        kept_[std::size_t(s)] = false;
    }
}

void SkipState::keep_result(int sensor, const Image* fused, const Metrics& metrics) {
    const std::size_t s = std::size_t(sensor);
    if (fused) kept_image_[s] = *fused;
    kept_metrics_[s] = metrics;
    pending_[s] = false;
    kept_[s] = true;
}

const Image& SkipState::skipped_image(int sensor) const {
    const std::size_t s = std::size_t(sensor);
    return outcomes_.at(s).reused ? kept_image_[s] : fused_[s];
}

std::vector<int> SkipState::detect() {
    detect_->submit_and_wait();
    scores_readback_.invalidate();
    const float* scores = static_cast<const float*>(scores_readback_.mapped());
    const std::size_t tiles = tiles_x_ * tiles_y_;
    const std::vector<int> fused = decide(scores, statics() ? scores + std::size_t(cfg_.sensors) * tiles : nullptr, nullptr);
    auto* args = static_cast<VkDispatchIndirectCommand*>(indirect_.mapped());
    for (std::size_t d = 0; d < dispatches_.size(); ++d)
        args[d] = {dispatches_[d][0], dispatches_[d][1], dispatches_[d][2] * std::uint32_t(fused.size())};
    if (sparse_ && !fused.empty()) sparse_->shrink(args);
    return fused;
}

std::vector<int> SkipState::decide(const float* scores, const float* still, const std::uint32_t* device_slots) {
    const std::size_t tiles = tiles_x_ * tiles_y_;
    std::vector<int> fused;
    if (sparse_) sparse_->begin_run();
    for (int s = 0; s < cfg_.sensors; ++s) {
        std::size_t changed = 0;
        std::vector<bool> changed_tiles(tiles);
        float top = 0;
        for (std::size_t t = 0; t < tiles; ++t) {
            const float v = scores[std::size_t(s) * tiles + t];
            // A NaN score (NaN never reaches an 8-bit plan) would count as changed.
            changed_tiles[t] = !(v <= cfg_.skip.threshold);
            changed += changed_tiles[t];
            top = std::max(top, v);
        }
        SkipOutcome& o = outcomes_[std::size_t(s)];
        o.idle = changed == 0;
        o.reused = false;
        if (!o.idle && still && kept_[std::size_t(s)]) {
            o.reused = true;
            for (std::size_t t = 0; t < tiles && o.reused; ++t) o.reused = still[std::size_t(s) * tiles + t] <= cfg_.skip.threshold;
        }
        const bool skipped = o.idle || o.reused;
        o.fused_region = skipped ? SkipRegion{} : SkipRegion{0, cfg_.height, 0, cfg_.width};
        if (!skipped && sparse_) {
            const auto choice = core::choose_sparse(cfg_.fusion, cfg_.height, cfg_.width, cfg_.frames, cfg_.channels,
                                                    changed_tiles, int(tiles_x_));
            sparse_->write(int(fused.size()), s, choice);
            o.fused_region = core::fused_region(choice, cfg_.height, cfg_.width);
        }
        o.fused_fraction = o.fused_region.share(cfg_.height, cfg_.width);
        o.changed_fraction = double(changed) / double(tiles);
        o.score = top;
        // The device applies the same rule to the same floats (skip_decide.comp).
        if (device_slots && device_slots[s] != (skipped ? kNotFused : std::uint32_t(fused.size())))
            throw Error(ErrorKind::Device, "internal: the device's skip decision for sensor " + std::to_string(s) +
                                               " differs from its scores'");
        slot_[std::size_t(s)] = skipped ? std::nullopt : std::optional<int>(int(fused.size()));
        if (!skipped) fused.push_back(s);
    }
    return fused;
}

Metrics SkipState::skipped_metrics(int sensor, const float* planar_background) {
    if (outcomes_.at(std::size_t(sensor)).reused) return kept_metrics_[std::size_t(sensor)];
    std::optional<Metrics>& cached = idle_metrics_.at(std::size_t(sensor));
    if (cached) return *cached;
    const ImageD image = convert<double>(fused_.at(std::size_t(sensor)));
    if (!planar_background) {
        cached = metrics_reference(image, nullptr, cfg_.metrics);
        return *cached;
    }
    ImageD background(image.height, image.width, image.channels);
    const std::size_t pixels = image.pixels(), C = std::size_t(image.channels);
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < C; ++c) background.data[p * C + c] = planar_background[c * pixels + p];
    cached = metrics_reference(image, &background, cfg_.metrics);
    return *cached;
}

}  // namespace vkfuse::vk

namespace vkfuse {

// Slot j < sensor s always, and slots fill in sensor order, so a sensor's
// frames are never overwritten before they are moved: they are copied again
// from the caller's views, which the detection already read.
void Plan::Impl::compact(std::span<const FrameView> frames, const std::vector<int>& fused_sensors) {
    const std::size_t K = std::size_t(cfg.frames);
    const std::size_t n = std::size_t(cfg.height) * std::size_t(cfg.width) * std::size_t(cfg.channels);
    auto* upload_bytes = static_cast<std::uint8_t*>(upload.mapped());
    for (std::size_t j = 0; j < fused_sensors.size(); ++j) {
        const std::size_t s = std::size_t(fused_sensors[j]);
        if (s != j)
            for (std::size_t k = 0; k < K; ++k)
                std::memcpy(upload_bytes + (j * K + k) * n, frames[s * K + k].data, n);
        if (!cfg.metrics.has(Metric::BackgroundDiff) || background_in_slot[j] == int(s)) continue;
        std::memcpy(static_cast<float*>(background.mapped()) + j * n, background_host.data() + s * n, n * sizeof(float));
        background_in_slot[j] = int(s);
    }
}

}  // namespace vkfuse

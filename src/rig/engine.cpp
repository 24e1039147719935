#include "rig/engine.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/sparse_wavelet.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::rig {
namespace {

class GpuEngine : public Engine {
public:
    GpuEngine(Context& context, const PlanConfig& config) : plan_(context, config) {}
    void set_background(int sensor, const Image& bg) override {
        if (plan_.config().metrics.has(Metric::BackgroundDiff)) plan_.set_background(sensor, FrameView::of(bg));
    }
    void set_skip_reference(int sensor, const SkipReference& r) override { plan_.set_skip_reference(sensor, r); }
    SkipOutcome skip_outcome(int sensor) override { return plan_.skip_outcome(sensor); }
    void run(std::span<const FrameView> frames) override { plan_.run(frames); }
    void submit(std::span<const FrameView> frames) override { plan_.submit(frames); }
    void collect() override { plan_.collect(); }
    int cycles_in_flight() const override { return plan_.config().cycles_in_flight; }
    const Image& fused(int sensor) override { return plan_.fused(sensor); }
    Metrics metrics(int sensor) override { return plan_.metrics(sensor); }
    std::uint64_t submits() const override { return plan_.submits(); }

private:
    Plan plan_;
};

// The double-precision reference, sensor by sensor; "submits" counts runs so
// the statistic means the same on both paths.
class CpuEngine : public Engine {
public:
    explicit CpuEngine(const PlanConfig& config)
        : cfg_(config),
          backgrounds_(std::size_t(config.sensors)),
          fused_(std::size_t(config.sensors)),
          metrics_(std::size_t(config.sensors)),
          skip_(std::size_t(config.sensors)),
          outcomes_(std::size_t(config.sensors)) {
        validate(cfg_.fusion, cfg_.height, cfg_.width, cfg_.channels, cfg_.frames);
    }
    void set_background(int sensor, const Image& bg) override {
        backgrounds_.at(std::size_t(sensor)) = convert<double>(bg);
        skip_.at(std::size_t(sensor)).idle_metrics.reset();
        skip_.at(std::size_t(sensor)).kept = false;
    }
    void set_skip_reference(int sensor, const SkipReference& r) override {
        check_skip_reference(r, cfg_.height, cfg_.width, cfg_.channels, cfg_.frames,
                             "skip reference of sensor " + std::to_string(sensor));
        SensorSkip& s = skip_.at(std::size_t(sensor));
        s.reference = r;
        std::vector<ImageD> means;
        for (const Image& m : r.mean) means.push_back(convert<double>(m));
        s.fused = convert<float>(fuse_reference(means, cfg_.fusion));
        s.idle_metrics.reset();
        s.kept = false;
    }
    SkipOutcome skip_outcome(int sensor) override { return outcomes_.at(std::size_t(sensor)); }
    void run(std::span<const FrameView> frames) override {
        if (frames.size() != std::size_t(cfg_.sensors) * std::size_t(cfg_.frames))
            throw Error(ErrorKind::InvalidArgument, "rig: frame count does not match sensors x frames");
        for (std::size_t s = 0; s < fused_.size(); ++s)
            run_sensor(s, frames.subspan(s * std::size_t(cfg_.frames), std::size_t(cfg_.frames)));
        ++runs_;
    }
    void submit(std::span<const FrameView> frames) override { run(frames); }
    void collect() override {}
    int cycles_in_flight() const override { return 1; }
    const Image& fused(int sensor) override { return fused_.at(std::size_t(sensor)); }
    Metrics metrics(int sensor) override { return metrics_.at(std::size_t(sensor)); }
    std::uint64_t submits() const override { return runs_; }

private:
    PlanConfig cfg_;
    std::vector<ImageD> backgrounds_;
    std::vector<Image> fused_;
    std::vector<Metrics> metrics_;
    struct SensorSkip {
        std::optional<SkipReference> reference;
        Image fused;  // the reference's means fused: an idle cycle's result
        std::optional<Metrics> idle_metrics;
        // SkipPolicy::Static: the last fused cycle's frames and result.
        bool kept = false;
        std::vector<std::vector<std::uint8_t>> previous;
        Image kept_image;
        Metrics kept_metrics;
    };
    std::vector<SensorSkip> skip_;
    std::vector<SkipOutcome> outcomes_;
    std::uint64_t runs_ = 0;

    // Skipping: whether sensor s's frames stayed within its noise of its
    // background (then its result is the fused reference) or, under
    // SkipPolicy::Static, of its last fused cycle (then that cycle's result),
    // as the device decides it.
    bool skipped(std::size_t s, std::span<const FrameView> frames) {
        if (cfg_.skip.policy == SkipPolicy::Off) return false;
        SensorSkip& sk = skip_[s];
        if (!sk.reference) throw Error(ErrorKind::InvalidArgument, "plan run: no skip reference set for sensor " + std::to_string(s));
        const std::vector<double> scores = change_scores_reference(frames, *sk.reference);
        SkipOutcome& o = outcomes_[s];
        std::vector<bool> changed_tiles;
        for (double v : scores) changed_tiles.push_back(!(v <= cfg_.skip.threshold));
        const auto changed = std::count(changed_tiles.begin(), changed_tiles.end(), true);
        o.idle = changed == 0;
        o.reused = !o.idle && sk.kept && still(s, frames);
        o.fused_region = o.idle || o.reused ? SkipRegion{} : SkipRegion{0, cfg_.height, 0, cfg_.width};
        if (!o.idle && !o.reused && cfg_.skip.policy == SkipPolicy::Tiles)
            o.fused_region = core::fused_region(core::choose_sparse(cfg_.fusion, cfg_.height, cfg_.width, cfg_.frames,
                                                                    cfg_.channels, changed_tiles,
                                                                    skip_tiles_x(cfg_.width)),
                                                cfg_.height, cfg_.width);
        o.fused_fraction = o.fused_region.share(cfg_.height, cfg_.width);
        o.changed_fraction = double(changed) / double(scores.size());
        o.score = *std::max_element(scores.begin(), scores.end());
        if (o.reused) {
            fused_[s] = sk.kept_image;
            metrics_[s] = sk.kept_metrics;
            return true;
        }
        if (!o.idle) return false;
        if (!cfg_.metrics.empty() && !sk.idle_metrics) sk.idle_metrics = metrics_of(s, convert<double>(sk.fused));
        if (!cfg_.metrics.empty()) metrics_[s] = *sk.idle_metrics;
        fused_[s] = sk.fused;
        return true;
    }

    Metrics metrics_of(std::size_t s, const ImageD& fused) const {
        const bool with_bg = cfg_.metrics.has(Metric::BackgroundDiff) && !backgrounds_[s].data.empty();
        return metrics_reference(fused, with_bg ? &backgrounds_[s] : nullptr, cfg_.metrics);
    }

    bool still(std::size_t s, std::span<const FrameView> frames) const {
        const SensorSkip& sk = skip_[s];
        std::vector<FrameView> previous;
        for (std::size_t k = 0; k < frames.size(); ++k) {
            FrameView v = frames[k];
            v.data = sk.previous[k].data();
            previous.push_back(v);
        }
        const std::vector<double> scores = static_scores_reference(frames, previous, *sk.reference);
        return std::all_of(scores.begin(), scores.end(), [&](double v) { return v <= cfg_.skip.threshold; });
    }

    void run_sensor(std::size_t s, std::span<const FrameView> frames) {
        if (skipped(s, frames)) return;
        std::vector<ImageD> images;
        for (const FrameView& v : frames) images.push_back(to_double(v));
        ImageD fused = fuse_reference(images, cfg_.fusion);
        // Tiles: outside the rectangle fused, the fused reference, as the device composes it.
        const SkipRegion& region = outcomes_[s].fused_region;
        if (cfg_.skip.policy == SkipPolicy::Tiles && region.height * region.width < cfg_.height * cfg_.width)
            for (int y = 0; y < fused.height; ++y)
                for (int x = 0; x < fused.width; ++x)
                    if (!region.contains(y, x, fused.height, fused.width))
                        for (int c = 0; c < fused.channels; ++c) fused.at(y, x, c) = skip_[s].fused.at(y, x, c);
        if (!cfg_.metrics.empty()) metrics_[s] = metrics_of(s, fused);
        fused_[s] = convert<float>(fused);
        if (!reuses_still_presses(cfg_.skip.policy)) return;
        SensorSkip& sk = skip_[s];
        sk.previous.clear();
        for (const FrameView& v : frames) {
            const auto* bytes = static_cast<const std::uint8_t*>(v.data);
            sk.previous.emplace_back(bytes, bytes + v.bytes());
        }
        sk.kept_image = fused_[s];
        sk.kept_metrics = metrics_[s];
        sk.kept = true;
    }
};

}  // namespace

std::unique_ptr<Engine> make_engine(Context* context, const PlanConfig& config) {
    if (context) return std::make_unique<GpuEngine>(*context, config);
    return std::make_unique<CpuEngine>(config);
}

ImageD to_double(const FrameView& v) {
    ImageD img(v.height, v.width, v.channels);
    for (std::size_t i = 0; i < img.data.size(); ++i)
        img.data[i] = v.type == PixelType::U8 ? double(static_cast<const std::uint8_t*>(v.data)[i]) / 255.0
                                              : double(static_cast<const float*>(v.data)[i]);
    return img;
}

}  // namespace vkfuse::rig

#include "rig/engine.hpp"

#include <vector>

#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::rig {
namespace {

class GpuEngine : public Engine {
public:
    GpuEngine(Context& context, const PlanConfig& config) : plan_(context, config) {}
    void set_background(int sensor, const Image& bg) override { plan_.set_background(sensor, FrameView::of(bg)); }
    void run(std::span<const FrameView> frames) override { plan_.run(frames); }
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
          metrics_(std::size_t(config.sensors)) {
        validate(cfg_.fusion, cfg_.height, cfg_.width, cfg_.channels, cfg_.frames);
    }
    void set_background(int sensor, const Image& bg) override {
        backgrounds_.at(std::size_t(sensor)) = convert<double>(bg);
    }
    void run(std::span<const FrameView> frames) override {
        if (frames.size() != std::size_t(cfg_.sensors) * std::size_t(cfg_.frames))
            throw Error(ErrorKind::InvalidArgument, "rig: frame count does not match sensors x frames");
        for (std::size_t s = 0; s < fused_.size(); ++s)
            run_sensor(s, frames.subspan(s * std::size_t(cfg_.frames), std::size_t(cfg_.frames)));
        ++runs_;
    }
    const Image& fused(int sensor) override { return fused_.at(std::size_t(sensor)); }
    Metrics metrics(int sensor) override { return metrics_.at(std::size_t(sensor)); }
    std::uint64_t submits() const override { return runs_; }

private:
    PlanConfig cfg_;
    std::vector<ImageD> backgrounds_;
    std::vector<Image> fused_;
    std::vector<Metrics> metrics_;
    std::uint64_t runs_ = 0;

    void run_sensor(std::size_t s, std::span<const FrameView> frames) {
        std::vector<ImageD> images;
        for (const FrameView& v : frames) images.push_back(to_double(v));
        const ImageD fused = fuse_reference(images, cfg_.fusion);
        const bool with_bg = cfg_.background_diff && !backgrounds_[s].data.empty();
        if (cfg_.want_metrics) metrics_[s] = metrics_reference(fused, with_bg ? &backgrounds_[s] : nullptr);
        fused_[s] = convert<float>(fused);
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

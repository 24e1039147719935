#include "stress_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "test_support.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::test {

Image random_frame(int height, int width, int channels, std::uint32_t seed) {
    return convert<float>(random_image(height, width, channels, seed));
}

Image structured_frame(int height, int width, int channels, std::uint32_t seed) {
    return convert<float>(structured_image(height, width, channels, seed));
}

std::vector<ImageD> to_double(const std::vector<Image>& frames) {
    std::vector<ImageD> out;
    out.reserve(frames.size());
    for (const Image& f : frames) out.push_back(convert<double>(f));
    return out;
}

Image scaled(const Image& image, float a) {
    Image out = image;
    for (float& v : out.data) v *= a;
    return out;
}

GpuCycle gpu_cycle(Context& ctx, const FusionSpec& spec, const std::vector<Image>& frames, int frames_per_sensor,
                   bool want_metrics) {
    const Image& first = frames.front();
    PlanConfig cfg;
    cfg.fusion = spec;
    cfg.height = first.height;
    cfg.width = first.width;
    cfg.channels = first.channels;
    cfg.frames = frames_per_sensor;
    cfg.sensors = int(frames.size()) / frames_per_sensor;
    cfg.metrics = want_metrics ? MetricSet{Metric::Sharpness, Metric::Contrast} : MetricSet{};
    Plan plan(ctx, cfg);
    std::vector<FrameView> views;
    for (const Image& f : frames) views.push_back(FrameView::of(f));
    plan.run(views);
    GpuCycle out;
    for (int s = 0; s < cfg.sensors; ++s) {
        out.fused.push_back(plan.fused(s));
        if (want_metrics) out.metrics.push_back(plan.metrics(s));
    }
    return out;
}

Metrics gpu_metrics(Context& ctx, const Image& image, const Image* background) {
    PlanConfig cfg;
    cfg.fuse = false;
    cfg.height = image.height;
    cfg.width = image.width;
    cfg.channels = image.channels;
    cfg.frames = 1;
    cfg.want_fused = false;
    cfg.metrics = cfg.metrics.with(Metric::BackgroundDiff, background != nullptr);
    Plan plan(ctx, cfg);
    if (background) plan.set_background(0, FrameView::of(*background));
    FrameView view = FrameView::of(image);
    plan.run(std::span(&view, 1));
    return plan.metrics(0);
}

template <class T>
long first_non_finite_of(const BasicImage<T>& image) {
    auto it = std::find_if(image.data.begin(), image.data.end(), [](T v) { return !std::isfinite(v); });
    return it == image.data.end() ? -1 : long(it - image.data.begin());
}

long first_non_finite(const Image& image) { return first_non_finite_of(image); }
long first_non_finite(const ImageD& image) { return first_non_finite_of(image); }

bool finite(const Metrics& m) {
    return std::isfinite(m.sharpness) && std::isfinite(m.contrast) &&
           (!m.background_diff || std::isfinite(*m.background_diff));
}

double max_abs(const ImageD& image) {
    double m = 0;
    for (double v : image.data) m = std::max(m, std::abs(v));
    return m;
}

double relative_error(double got, double ref) {
    if (ref == 0) return got == 0 ? 0 : std::numeric_limits<double>::infinity();
    return std::abs(got - ref) / std::abs(ref);
}

Mismatch compare(const Image& gpu, const ImageD& ref, double tolerance) {
    Mismatch m;
    if (!(gpu.height == ref.height && gpu.width == ref.width && gpu.channels == ref.channels)) {
        m.over = ref.size() + 1;
        m.worst = std::numeric_limits<double>::infinity();
        return m;
    }
    for (std::size_t i = 0; i < ref.data.size(); ++i) {
        const double d = std::abs(double(gpu.data[i]) - ref.data[i]);
        m.worst = std::max(m.worst, std::isnan(d) ? std::numeric_limits<double>::infinity() : d);
        m.over += !(d <= tolerance);
    }
    return m;
}

FusionSpec method_spec(Method method, int levels) {
    FusionSpec s;
    s.method = method;
    s.levels = levels;
    return s;
}

FusionSpec wavelet_spec(Wavelet wavelet, WaveletMode mode, int levels) {
    FusionSpec s = method_spec(Method::Wavelet, levels);
    s.wavelet = wavelet;
    s.mode = mode;
    return s;
}

std::string describe(const FusionSpec& s) {
    std::string text(to_string(s.method));
    if (s.method == Method::Wavelet) text += " " + std::string(to_string(s.wavelet)) + "/" + std::string(to_string(s.mode));
    if (s.method == Method::Wavelet || s.method == Method::Laplacian)
        text += " L=" + std::to_string(s.effective_levels()) + " " + std::string(to_string(s.base_rule)) + "/" +
                std::string(to_string(s.detail_rule));
    return text;
}

std::vector<FusionSpec> every_method() {
    std::vector<FusionSpec> specs{method_spec(Method::Brovey), method_spec(Method::ChannelSum),
                                  method_spec(Method::Laplacian)};
    for (Wavelet w : kAllWavelets)
        for (WaveletMode m : kAllModes) specs.push_back(wavelet_spec(w, m, 3));
    return specs;
}

FusionSpec tie_free(FusionSpec s) {
    s.base_rule = Rule::Mean;
    s.detail_rule = Rule::Max;
    return s;
}

int levels_to_one_pixel(int height, int width) {
    int levels = 0;
    while (height > 1 || width > 1) {
        height = (height + 1) / 2;
        width = (width + 1) / 2;
        ++levels;
    }
    return levels;
}

void report(const std::string& what, double value) { std::printf("[ worst    ] %s: %.3g\n", what.c_str(), value); }

}  // namespace vkfuse::test

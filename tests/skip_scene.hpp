// skip_scene.hpp - scenes for the skipping tests: K background means with a
// per-pixel deviation, frames drawn from them with noise, and presses.
#pragma once
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "vkfuse/core/skip.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::test {

using Bytes = std::vector<std::uint8_t>;

// A scene: K background means with a per-pixel deviation, and frames drawn
// from it with noise of that deviation.
struct Scene {
    int h, w, c, k;
    SkipReference reference;
};

inline Scene make_scene(int h, int w, int c, int k, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> level(0.2f, 0.8f), spread(1.0f / 255, 3.0f / 255);
    Scene s{h, w, c, k, {}};
    for (int i = 0; i < k; ++i) {
        Image mean(h, w, c), dev(h, w, c);
        for (float& v : mean.data) v = level(rng);
        for (float& v : dev.data) v = spread(rng);
        s.reference.mean.push_back(std::move(mean));
        s.reference.deviation.push_back(std::move(dev));
    }
    return s;
}

// A rectangle of pixels a press moves: rows y0 .. y1 - 1, columns x0 .. x1 - 1.
struct Press {
    int y0 = 0, y1 = 0, x0 = 0, x1 = 0;
};

// K frames of the scene, noise of the given number of deviations at most,
// and the pixels of every press moved by 0.3.

inline std::vector<Bytes> frames_of(const Scene& s, std::uint32_t seed, double noise, const std::vector<Press>& presses) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Bytes> out;
    for (int k = 0; k < s.k; ++k) {
        Bytes f(std::size_t(s.h) * s.w * s.c);
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x)
                for (int ch = 0; ch < s.c; ++ch) {
                    const std::size_t i = (std::size_t(y) * s.w + x) * s.c + ch;
                    double v = s.reference.mean[k].data[i] + noise * u(rng) * s.reference.deviation[k].data[i];
                    for (const Press& p : presses)
                        if (y >= p.y0 && y < p.y1 && x >= p.x0 && x < p.x1) v += 0.3;
                    f[i] = std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255));
                }
        out.push_back(std::move(f));
    }
    return out;
}

// With `press`: the square from a third to half of each side.
inline std::vector<Bytes> frames_of(const Scene& s, std::uint32_t seed, double noise, bool press) {
    return frames_of(s, seed, noise, press ? std::vector<Press>{{s.h / 3, s.h / 2, s.w / 3, s.w / 2}} : std::vector<Press>{});
}

inline std::vector<FrameView> views(const Scene& s, const std::vector<std::vector<Bytes>>& sensors) {
    std::vector<FrameView> v;
    for (const auto& frames : sensors)
        for (const Bytes& f : frames) v.push_back({f.data(), s.h, s.w, s.c, PixelType::U8});
    return v;
}

inline PlanConfig skip_config(const Scene& s, int sensors, FusionSpec spec, SkipPolicy policy, double threshold) {
    PlanConfig cfg;
    cfg.fusion = spec;
    cfg.height = s.h;
    cfg.width = s.w;
    cfg.channels = s.c;
    cfg.frames = s.k;
    cfg.sensors = sensors;
    cfg.input = PixelType::U8;
    cfg.metrics = MetricSet::all();
    cfg.skip = {policy, threshold};
    return cfg;
}

}  // namespace vkfuse::test

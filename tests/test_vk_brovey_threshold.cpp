// Brovey's dark-pixel threshold on the GPU (docs/spec.md: s >= 1e-6 takes the
// ratio sum_k (p_k / s) I_k, else the mean; p_k = max(I_k, 0)). The sums
// below lie clearly on one side of 1e-6 in float32 as in double, plus the
// float32 neighbours of 1e-6 and float(1e-6) itself (9.99999997e-7: below
// 1e-6, so the mean, although a float comparison with the literal 1e-6, which
// rounds to that very float, would say otherwise; test_cpu_brovey_threshold.cpp
// pins the exact double boundary). A negative third frame makes the mean
// (about -0.083) far from the ratio (about s): a pixel on the wrong side is off
// by 0.08, where the tolerance is 1e-5.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

constexpr float kNegative = -0.25f;

struct Pixel {
    float i0, i1;
    bool ratio;  // which side of 1e-6 their sum lies on
};

double ratio_of(const Pixel& p) {
    const double s = double(p.i0) + double(p.i1);
    return (p.i0 / s) * p.i0 + (p.i1 / s) * p.i1;
}
double mean_of(const Pixel& p) { return (double(p.i0) + double(p.i1) + kNegative) / 3.0; }

std::vector<Pixel> threshold_cases() {
    const float one = 1e-6f;
    return {
        {0.3e-6f, 0.2e-6f, false},  // s = 0.5e-6
        {0.6e-6f, 0.3e-6f, false},  // s = 0.9e-6
        {0.5e-6f, 0.49e-6f, false},  // s = 0.99e-6
        {std::nextafter(one, 0.0f), 0.0f, false},  // the float below float(1e-6): below 1e-6 either way
        {one, 0.0f, false},                        // float(1e-6) itself: below 1e-6
        {std::nextafter(one, 1.0f), 0.0f, true},   // the float above it: above 1e-6 either way
        {0.51e-6f, 0.5e-6f, true},  // s = 1.01e-6
        {0.6e-6f, 0.5e-6f, true},   // s = 1.1e-6
        {0.7e-5f, 0.3e-5f, true},   // s = 1e-5
        {1e-5f, 0.0f, true},
        {0.25e-4f, 0.75e-4f, true},  // s = 1e-4
        {1e-4f, 0.0f, true},
        {0.2f, 0.5f, true},
        {0.0f, 0.0f, false},
    };
}

class VulkanBroveyThreshold : public VulkanTest {};

// Two sensors in one plan: the second also carries a bright pixel (3000) in
// another column, so a per-sensor scaling of the frames cannot move its
// threshold decisions either.
TEST_F(VulkanBroveyThreshold, MeanBelowRatioAbove) {
    const std::vector<Pixel> cases = threshold_cases();
    const int n = int(cases.size()) + 1;
    std::vector<Image> frames;  // sensor-major: s * 3 + k
    for (int s = 0; s < 2; ++s)
        for (int k = 0; k < 3; ++k) {
            Image f(1, n, 1);
            for (int x = 0; x < n - 1; ++x) {
                const Pixel& p = cases[std::size_t(x)];
                f.at(0, x, 0) = k == 0 ? p.i0 : k == 1 ? p.i1 : kNegative;
            }
            f.at(0, n - 1, 0) = s == 1 ? 3000.0f : 0.5f;
            frames.push_back(f);
        }
    FusionSpec spec;
    spec.method = Method::Brovey;
    PlanConfig cfg;
    cfg.fusion = spec;
    cfg.height = 1;
    cfg.width = n;
    cfg.channels = 1;
    cfg.frames = 3;
    cfg.sensors = 2;
    cfg.metrics = {};
    Plan plan = run_plan(ctx(), cfg, frames);
    for (int s = 0; s < 2; ++s) {
        SCOPED_TRACE("sensor " + std::to_string(s));
        std::vector<ImageD> mine;
        for (int k = 0; k < 3; ++k) mine.push_back(convert<double>(frames[std::size_t(s * 3 + k)]));
        const ImageD ref = fuse_reference(mine, spec);
        const Image& gpu = plan.fused(s);
        for (int x = 0; x < n - 1; ++x) {
            const Pixel& p = cases[std::size_t(x)];
            SCOPED_TRACE("s = " + std::to_string((double(p.i0) + double(p.i1)) * 1e6) + "e-6");
            const double want = p.ratio ? ratio_of(p) : mean_of(p);
            EXPECT_NEAR(gpu.at(0, x, 0), want, 1e-5) << (p.ratio ? "expected the ratio" : "expected the mean");
            EXPECT_NEAR(ref.at(0, x, 0), want, 1e-12) << "reference: " << (p.ratio ? "ratio" : "mean");
        }
        EXPECT_NEAR(gpu.at(0, n - 1, 0), s == 1 ? 3000.0 : 0.5, 1e-3);  // equal frames: the ratio is the value
    }
}

}  // namespace
}  // namespace vkfuse::test

// Brovey's dark-pixel threshold in the CPU reference (docs/spec.md: with
// p_k = max(I_k, 0) and s = sum_k p_k, I* = sum_k (p_k / s) I_k when
// s >= 1e-6, else mean_k I_k). Each pixel below is one case; a negative third
// frame makes the mean (about -0.083) far from the ratio (about s), so a pixel
// on the wrong side of the threshold is off by 0.08.
// test_vk_brovey_threshold.cpp asks the same of the GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

constexpr double kNegative = -0.25;  // the third frame everywhere: p = 0, pulls the mean down

struct Pixel {
    double i0, i1;  // the two positive frames: s = i0 + i1
    bool ratio;     // docs/spec.md: s >= 1e-6
};

double ratio_of(const Pixel& p) {
    const double s = p.i0 + p.i1;
    return (p.i0 / s) * p.i0 + (p.i1 / s) * p.i1;  // the negative frame weighs 0
}
double mean_of(const Pixel& p) { return (p.i0 + p.i1 + kNegative) / 3.0; }

TEST(CpuBroveyThreshold, MeanBelowRatioFromExactly1e6) {
    const double below = std::nextafter(1e-6, 0.0), above = std::nextafter(1e-6, 1.0);
    const std::vector<Pixel> pixels{
        {0.3e-6, 0.2e-6, false},   // s = 0.5e-6
        {0.6e-6, 0.3e-6, false},   // s = 0.9e-6
        {below, 0.0, false},       // the largest double below 1e-6
        {1e-6, 0.0, true},         // exactly 1e-6: s >= 1e-6 takes the ratio
        {above, 0.0, true},
        {0.6e-6, 0.5e-6, true},    // s = 1.1e-6
        {0.7e-5, 0.3e-5, true},    // s = 1e-5
        {0.25e-4, 0.75e-4, true},  // s = 1e-4
        {0.2, 0.5, true},
        {0.0, 0.0, false},         // all dark
    };
    const int n = int(pixels.size());
    std::vector<ImageD> frames(3, ImageD(1, n, 1));
    for (int x = 0; x < n; ++x) {
        frames[0].at(0, x, 0) = pixels[std::size_t(x)].i0;
        frames[1].at(0, x, 0) = pixels[std::size_t(x)].i1;
        frames[2].at(0, x, 0) = kNegative;
    }
    FusionSpec spec;
    spec.method = Method::Brovey;
    const ImageD fused = fuse_reference(frames, spec);
    for (int x = 0; x < n; ++x) {
        const Pixel& p = pixels[std::size_t(x)];
        SCOPED_TRACE("s = " + std::to_string((p.i0 + p.i1) * 1e6) + "e-6");
        const double want = p.ratio ? ratio_of(p) : mean_of(p);
        const double other = p.ratio ? mean_of(p) : (p.i0 + p.i1 > 0 ? ratio_of(p) : 0.0);
        ASSERT_GT(std::abs(want - other), 0.05);  // the two formulas are told apart
        EXPECT_NEAR(fused.at(0, x, 0), want, 1e-15) << (p.ratio ? "expected the ratio" : "expected the mean");
    }
}

// The same decision per channel and for any K: in a 3-channel image each
// channel has its own s.
TEST(CpuBroveyThreshold, DecidedPerChannel) {
    std::vector<ImageD> frames(2, ImageD(1, 1, 3));
    const double i0[3] = {0.9e-6, 1.1e-6, 0.5};
    for (int c = 0; c < 3; ++c) {
        frames[0].at(0, 0, c) = i0[c];
        frames[1].at(0, 0, c) = -0.5;
    }
    FusionSpec spec;
    spec.method = Method::Brovey;
    const ImageD fused = fuse_reference(frames, spec);
    EXPECT_NEAR(fused.at(0, 0, 0), (0.9e-6 - 0.5) / 2, 1e-15);  // below: the mean
    EXPECT_NEAR(fused.at(0, 0, 1), 1.1e-6, 1e-15);              // above: the ratio, = i0 alone
    EXPECT_NEAR(fused.at(0, 0, 2), 0.5, 1e-15);
}

}  // namespace
}  // namespace vkfuse::test

// Exact max-abs ties on the GPU (docs/spec.md "Rules": ties go to the lowest frame
// index). Every transform here is linear and float rounding is symmetric in
// sign, so the coefficients of -A are exactly the negated coefficients of A:
// every coefficient ties, and the rule alone decides which image comes back.
// Fusing A with -A under max-abs (base and detail) must reconstruct A; with
// the frames swapped, -A. Random frames never tie exactly, which is why the
// GPU-against-reference tests (test_vk_fusion.cpp) cannot see this.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

// Reconstruction error of a float32 pyramid / wavelet round trip is ~1e-6;
// taking the other frame at a tie is off by 2|A| (up to ~2).
constexpr double kTolerance = 1e-5;

std::string describe(const FusionSpec& s) {
    return std::string(to_string(s.method)) +
           (s.method == Method::Wavelet ? " " + std::string(to_string(s.wavelet)) + "/" + std::string(to_string(s.mode))
                                        : std::string()) +
           " L=" + std::to_string(s.effective_levels());
}

// Signed values of both signs, with structure (so every band carries energy).
ImageD signed_image(int h, int w, int c, std::uint32_t seed) {
    ImageD a = structured_image(h, w, c, seed);
    for (double& v : a.data) v = double(float(v - 0.4));
    return a;
}

ImageD scaled(const ImageD& a, double k) {  // k a power of two: exact in float
    ImageD out = a;
    for (double& v : out.data) v *= k;
    return out;
}

double max_abs_error(const Image& got, const ImageD& want) {
    EXPECT_TRUE(got.height == want.height && got.width == want.width && got.channels == want.channels);
    double worst = 0;
    for (std::size_t i = 0; i < want.data.size(); ++i)
        worst = std::max(worst, std::abs(double(got.data[i]) - want.data[i]));
    return worst;
}

// Runs one plan of S sensors x K frames; sensor s must come back as expected[s].
void check_ties(Context& ctx, const FusionSpec& spec, const std::vector<ImageD>& frames, int k,
                const std::vector<ImageD>& expected) {
    SCOPED_TRACE(describe(spec) + ", K=" + std::to_string(k));
    const ImageD& a = frames[0];
    PlanConfig cfg;
    cfg.fusion = spec;
    cfg.height = a.height;
    cfg.width = a.width;
    cfg.channels = a.channels;
    cfg.frames = k;
    cfg.sensors = int(expected.size());
    cfg.metrics = {};
    std::vector<Image> f32;
    for (const ImageD& f : frames) f32.push_back(convert<float>(f));
    Plan plan = run_plan(ctx, cfg, f32);
    for (std::size_t s = 0; s < expected.size(); ++s) {
        SCOPED_TRACE("sensor " + std::to_string(s));
        EXPECT_LE(max_abs_error(plan.fused(int(s)), expected[s]), kTolerance);
        // The reference decides the same ties the same way.
        const ImageD ref = fuse_reference(std::span(frames).subspan(s * std::size_t(k), std::size_t(k)), spec);
        EXPECT_LE(max_abs_diff(ref, expected[s]), 1e-9);
    }
}

class VulkanMaxAbsTies : public VulkanTest {};

// Two frames that tie everywhere: sensor 0 fuses (A, -A) and must give A,
// sensor 1 fuses (-A, A) and must give -A (the lowest index wins, not the
// positive value).
TEST_F(VulkanMaxAbsTies, TwoFramesTieToTheFirst) {
    const ImageD a = signed_image(80, 97, 3, 7), neg = scaled(a, -1.0);
    for (const FusionSpec& spec : every_pyramid_and_wavelet_max_abs()) check_ties(ctx(), spec, {a, neg, neg, a}, 2, {a, neg});
}

// Three frames where the first and the last tie and the middle one is smaller
// everywhere (half of A: its coefficients are exactly half of A's).
TEST_F(VulkanMaxAbsTies, FirstAndLastOfThreeTieToTheFirst) {
    const ImageD a = signed_image(80, 97, 1, 8), neg = scaled(a, -1.0), half = scaled(a, 0.5);
    for (const FusionSpec& spec : every_pyramid_and_wavelet_max_abs())
        check_ties(ctx(), spec, {a, half, neg, neg, half, a}, 3, {a, neg});
}

// The same on frames whose width is a multiple of 4, where the rule and the
// Laplacian kernels take their vector paths (four pixels an invocation): every
// lane of a quad meets an exact tie.
TEST_F(VulkanMaxAbsTies, TiesGoToTheFirstOnWholeQuadsToo) {
    const ImageD a = signed_image(80, 96, 3, 9), neg = scaled(a, -1.0), half = scaled(a, 0.5);
    for (const FusionSpec& spec : every_pyramid_and_wavelet_max_abs()) {
        check_ties(ctx(), spec, {a, neg, neg, a}, 2, {a, neg});
        check_ties(ctx(), spec, {a, half, neg, neg, half, a}, 3, {a, neg});
    }
}

}  // namespace
}  // namespace vkfuse::test

// The GPU background model (mean of N frames) against the double reference,
// and the plan's F32 background for an 8-bit plan.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "expect_error.hpp"
#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/rig/background.hpp"

namespace vkfuse::test {
namespace {

std::vector<std::vector<std::uint8_t>> noisy_frames(int n, int h, int w, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> level(0, 255);
    std::vector<std::vector<std::uint8_t>> frames(std::size_t(n), std::vector<std::uint8_t>(std::size_t(h) * w * 3));
    for (auto& f : frames)
        for (auto& v : f) v = std::uint8_t(level(rng));
    return frames;
}

std::vector<FrameView> views_of(const std::vector<std::vector<std::uint8_t>>& frames, int h, int w) {
    std::vector<FrameView> views;
    for (const auto& f : frames) views.push_back({f.data(), h, w, 3, PixelType::U8});
    return views;
}

class VulkanBackground : public VulkanTest {};

// The reference itself: the plain mean, per pixel and channel.
TEST(BackgroundReference, IsThePlainMean) {
    const auto frames = noisy_frames(3, 2, 5, 9);
    const ImageD mean = background_mean_reference(views_of(frames, 2, 5));
    for (std::size_t i = 0; i < mean.data.size(); ++i)
        EXPECT_DOUBLE_EQ(mean.data[i], (frames[0][i] + frames[1][i] + frames[2][i]) / 255.0 / 3.0) << i;
    EXPECT_THROW(parse_method("mean"), Error);  // a plan kind of its own: the CLI offers no such fusion method
}

// The paper's 100 frames at odd sizes, and a long run that a plain float sum
// would drift on: Kahan summation keeps the GPU mean within a few float ulps.
TEST_F(VulkanBackground, MeanMatchesReference) {
    for (auto [n, h, w] : {std::tuple{100, 61, 97}, {1, 5, 7}, {3, 240, 320}, {400, 17, 13}}) {
        SCOPED_TRACE(std::to_string(n) + " frames of " + std::to_string(h) + "x" + std::to_string(w));
        const auto frames = noisy_frames(n, h, w, std::uint32_t(n + h));
        const auto views = views_of(frames, h, w);
        BackgroundModel model(ctx(), h, w, 3, n);
        const Image gpu = model.mean(views);
        EXPECT_LE(max_abs_diff(gpu, background_mean_reference(views)), 1e-6);
    }
}

TEST_F(VulkanBackground, ReusedForEveryCallAndFloatInput) {
    const int h = 9, w = 11;
    BackgroundModel model(ctx(), h, w, 1, 4, PixelType::F32);
    for (std::uint32_t seed : {1u, 2u}) {
        std::vector<Image> images;
        std::vector<FrameView> views;
        for (std::uint32_t k = 0; k < 4; ++k) images.push_back(convert<float>(random_image(h, w, 1, seed * 10 + k)));
        for (const Image& img : images) views.push_back(FrameView::of(img));
        EXPECT_LE(max_abs_diff(model.mean(views), background_mean_reference(views)), 1e-7);
    }
}

TEST_F(VulkanBackground, WrongFrameCountIsAnError) {
    BackgroundModel model(ctx(), 4, 4, 3, 5);
    const auto frames = noisy_frames(4, 4, 4, 1);
    expect_error([&] { model.mean(views_of(frames, 4, 4)); }, "background model", ErrorKind::InvalidArgument,
                 "got 4 frames, built for 5");
}

// A rig fuses 8-bit frames but its background is a float mean: an 8-bit plan
// takes a float background as it is, not rounded to 8 bits.
TEST_F(VulkanBackground, EightBitPlanTakesFloatBackground) {
    const int h = 16, w = 24;
    const auto frames = noisy_frames(1, h, w, 7);
    const Image bg = convert<float>(random_image(h, w, 3, 3));
    PlanConfig cfg{FusionSpec{}, h, w, 3, 1, 1, PixelType::U8};
    cfg.fuse = false;
    cfg.want_fused = false;
    cfg.metrics = MetricSet::all();
    Plan plan(ctx(), cfg);
    plan.set_background(0, FrameView::of(bg));
    plan.run(views_of(frames, h, w));
    const ImageD ref_bg = convert<double>(bg);
    const Metrics ref = metrics_reference(background_mean_reference(views_of(frames, h, w)), &ref_bg);
    ASSERT_TRUE(plan.metrics(0).background_diff);
    EXPECT_NEAR(*plan.metrics(0).background_diff, *ref.background_diff, 1e-5 * *ref.background_diff);
    EXPECT_EQ(plan.submits(), 1u);
}

}  // namespace
}  // namespace vkfuse::test

// GPU metric reductions where float32 summation fails first: 8192 x 8192
// (67M terms), constant images (the contrast must come out exactly 0, not a
// rounding residue) and a nearly flat image (standard deviation 1e-4 on a mean
// of 0.999, so the deviations are 1e-4 of the values they are taken from).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "stress_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

constexpr double kRelTolerance = 1e-5;      // docs/spec.md: each metric, relative
constexpr double kFlatTolerance = 1e-3;     // contrast of the nearly flat image

std::string shape(const Image& img) {
    return std::to_string(img.height) + "x" + std::to_string(img.width) + "x" + std::to_string(img.channels);
}

void expect_metrics(Context& ctx, const std::string& label, const Image& img, const Image* bg = nullptr,
                    double contrast_tolerance = kRelTolerance) {
    const std::string what = label + " " + shape(img);
    SCOPED_TRACE(what);
    ImageD ref_bg = bg ? convert<double>(*bg) : ImageD();
    const Metrics ref = metrics_reference(convert<double>(img), bg ? &ref_bg : nullptr);
    const Metrics gpu = gpu_metrics(ctx, img, bg);
    const double sharp = relative_error(gpu.sharpness, ref.sharpness);
    const double contrast = relative_error(gpu.contrast, ref.contrast);
    EXPECT_LE(sharp, kRelTolerance) << "sharpness gpu " << gpu.sharpness << " ref " << ref.sharpness;
    EXPECT_LE(contrast, contrast_tolerance) << "contrast gpu " << gpu.contrast << " ref " << ref.contrast;
    report(what + " sharpness rel", sharp);
    report(what + " contrast rel", contrast);
    if (bg) {
        ASSERT_TRUE(gpu.background_diff && ref.background_diff);
        const double diff = relative_error(*gpu.background_diff, *ref.background_diff);
        EXPECT_LE(diff, kRelTolerance) << "background_diff gpu " << *gpu.background_diff;
        report(what + " background_diff rel", diff);
    }
}

Image constant(int h, int w, int c, std::initializer_list<float> per_channel) {
    Image img(h, w, c);
    for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = per_channel.begin()[i % std::size_t(c)];
    return img;
}

// Mean 0.999, standard deviation 1e-4, tails cut at 9 sigma so every value stays below 1.
Image nearly_flat(int h, int w, int c, std::uint32_t seed) {
    Image img(h, w, c);
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1e-4f);
    for (float& v : img.data) v = 0.999f + std::clamp(noise(rng), -9e-4f, 9e-4f);
    return img;
}

class StressMetrics : public VulkanTest {};

// A constant image has sharpness 0 and contrast 0 exactly; anything else is a
// rounding residue of the mean, which would be an infinite relative error.
TEST_F(StressMetrics, ConstantImagesAreExactlyFlat) {
    for (auto [h, w] : {std::pair{1, 1}, {1, 4097}, {4097, 1}, {257, 263}})
        for (float v : {0.0f, 1.0f, 0.999f, 0.1f, 1.0f / 3.0f}) expect_metrics(ctx(), "constant", constant(h, w, 1, {v}));
    expect_metrics(ctx(), "constant rgb", constant(509, 1021, 3, {0.2f, 0.7f, 0.999f}));
    expect_metrics(ctx(), "constant", constant(8192, 8192, 1, {0.999f}));
}

TEST_F(StressMetrics, RandomImagesUpTo8192) {
    const Image bg = random_frame(8192, 8192, 1, 2);
    expect_metrics(ctx(), "random", random_frame(8192, 8192, 1, 1), &bg);
    expect_metrics(ctx(), "random odd", random_frame(1021, 1031, 3, 3));
}

TEST_F(StressMetrics, NearlyFlatContrast) {
    expect_metrics(ctx(), "nearly flat", nearly_flat(8192, 8192, 1, 4), nullptr, kFlatTolerance);
    expect_metrics(ctx(), "nearly flat", nearly_flat(4096, 4096, 3, 5), nullptr, kFlatTolerance);
    expect_metrics(ctx(), "nearly flat", nearly_flat(61, 97, 1, 6), nullptr, kFlatTolerance);
}

}  // namespace
}  // namespace vkfuse::test

// GPU metric reductions against the double reference, up to 4096 x 4096.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

constexpr double kRelTolerance = 1e-5;  // docs/spec.md: each metric, relative

void expect_close(double gpu, double ref, const char* what) {
    if (ref == 0.0)
        EXPECT_LE(std::abs(gpu), 1e-7) << what;
    else
        EXPECT_LE(std::abs(gpu - ref) / std::abs(ref), kRelTolerance) << what << ": gpu " << gpu << " ref " << ref;
}

Metrics gpu_metrics(Context& ctx, const ImageD& img, const ImageD* bg) {
    PlanConfig cfg{FusionSpec{}, img.height, img.width, img.channels, 1, 1};
    cfg.fuse = false;
    cfg.want_fused = false;
    cfg.metrics = cfg.metrics.with(Metric::BackgroundDiff, bg != nullptr);
    Plan plan(ctx, cfg);
    Image f = convert<float>(img);
    Image b;
    if (bg) {
        b = convert<float>(*bg);
        plan.set_background(0, FrameView::of(b));
    }
    std::vector<FrameView> views{FrameView::of(f)};
    plan.run(views);
    return plan.metrics(0);
}

void check_metrics(Context& ctx, const ImageD& img, const ImageD& bg) {
    SCOPED_TRACE(std::to_string(img.height) + "x" + std::to_string(img.width) + "x" + std::to_string(img.channels));
    Metrics ref = metrics_reference(img, &bg);
    Metrics gpu = gpu_metrics(ctx, img, &bg);
    expect_close(gpu.sharpness, ref.sharpness, "sharpness");
    expect_close(gpu.contrast, ref.contrast, "contrast");
    ASSERT_TRUE(gpu.background_diff && ref.background_diff);
    expect_close(*gpu.background_diff, *ref.background_diff, "background_diff");
}

class VulkanMetrics : public VulkanTest {};

TEST_F(VulkanMetrics, OddAndTinySizes) {
    std::uint32_t seed = 1;
    for (auto [h, w] : {std::pair{1, 1}, {1, 7}, {7, 1}, {2, 3}, {5, 7}, {61, 97}, {240, 320}, {481, 641}})
        for (int c : {1, 3}) {
            check_metrics(ctx(), random_image(h, w, c, seed), structured_image(h, w, c, seed + 1));
            seed += 2;
        }
}

TEST_F(VulkanMetrics, LargestSize4096) {
    const ImageD image = random_image(4096, 4096, 3, 7), background = structured_image(4096, 4096, 3, 8);
    if (!has_device_addresses()) {
        // One such sensor's planes exceed one binding (128 MiB on lavapipe):
        // without device addresses the plan is refused, in one line.
        expect_error([&] { gpu_metrics(ctx(), image, &background); }, ctx().device().name, ErrorKind::Device,
                     "needs device addresses (bufferDeviceAddress), which the device lacks");
        return;
    }
    check_metrics(ctx(), image, background);
}

TEST_F(VulkanMetrics, RealDigitFrame) {
    ImageD frame = convert<double>(io::read_image(data_path("digit_bg_tacto.png")));
    ImageD shifted = frame;
    for (auto& v : shifted.data) v = v * 0.9 + 0.05;
    check_metrics(ctx(), frame, shifted);
}

TEST_F(VulkanMetrics, ConstantImageHasNoSharpnessNorContrast) {
    ImageD flat(64, 48, 3);
    for (auto& v : flat.data) v = 0.5;
    Metrics m = gpu_metrics(ctx(), flat, nullptr);
    EXPECT_EQ(m.sharpness, 0.0);
    EXPECT_LE(m.contrast, 1e-7);
    EXPECT_FALSE(m.background_diff.has_value());
}

TEST_F(VulkanMetrics, EverySensorOfABatchIsScoredOnItsOwn) {
    const int S = 4;
    PlanConfig cfg{FusionSpec{}, 50, 70, 3, 1, S};
    cfg.fuse = false;
    cfg.want_fused = true;
    std::vector<ImageD> frames;
    std::vector<Image> f32;
    for (int i = 0; i < S; ++i) {
        frames.push_back(i % 2 ? random_image(50, 70, 3, 200 + i) : structured_image(50, 70, 3, 200 + i));
        f32.push_back(convert<float>(frames.back()));
    }
    Plan plan = run_plan(ctx(), cfg, f32);
    for (int i = 0; i < S; ++i) {
        SCOPED_TRACE("sensor " + std::to_string(i));
        Metrics ref = metrics_reference(frames[std::size_t(i)]);
        expect_close(plan.metrics(i).sharpness, ref.sharpness, "sharpness");
        expect_close(plan.metrics(i).contrast, ref.contrast, "contrast");
        EXPECT_LE(max_abs_diff(plan.fused(i), frames[std::size_t(i)]), 0.0);
    }
}

// Every non-empty subset of the metrics, on a fusing plan of two sensors: the
// metrics asked for are the bits the plan that computes all three gives (each
// is summed on its own), the others NaN or absent, on the device and in the
// reference alike.
TEST_F(VulkanMetrics, APlanComputesOnlyTheMetricsAskedFor) {
    const int S = 2, K = 2, h = 75, w = 96;
    std::vector<Image> frames, backgrounds;
    for (int i = 0; i < S * K; ++i) frames.push_back(convert<float>(structured_image(h, w, 3, 300 + i)));
    for (int i = 0; i < S; ++i) backgrounds.push_back(convert<float>(random_image(h, w, 3, 400 + i)));
    const auto run = [&](MetricSet which) {
        PlanConfig cfg{FusionSpec{}, h, w, 3, K, S};
        cfg.metrics = which;
        Plan plan(ctx(), cfg);
        if (which.has(Metric::BackgroundDiff))
            for (int s = 0; s < S; ++s) plan.set_background(s, FrameView::of(backgrounds[std::size_t(s)]));
        std::vector<FrameView> views;
        for (const Image& f : frames) views.push_back(FrameView::of(f));
        plan.run(views);
        std::vector<Metrics> out;
        for (int s = 0; s < S; ++s) out.push_back(plan.metrics(s));
        return std::pair(out, plan.fused(0));
    };
    const auto [all, fused] = run(MetricSet::all());
    const Metrics ref_all = metrics_reference(convert<double>(fused), nullptr);
    for (unsigned bits = 1; bits < 8; ++bits) {
        MetricSet which;
        for (Metric m : kAllMetrics) which = which.with(m, (bits >> unsigned(m)) & 1u);
        SCOPED_TRACE(which.to_string());
        const auto [got, image] = run(which);
        EXPECT_EQ(max_abs_diff(image, convert<double>(fused)), 0.0);
        for (int s = 0; s < S; ++s) {
            const Metrics& g = got[std::size_t(s)];
            const Metrics& a = all[std::size_t(s)];
            if (which.has(Metric::Sharpness)) {
                EXPECT_EQ(g.sharpness, a.sharpness);
            } else {
                EXPECT_TRUE(std::isnan(g.sharpness));
            }
            if (which.has(Metric::Contrast)) {
                EXPECT_EQ(g.contrast, a.contrast);
            } else {
                EXPECT_TRUE(std::isnan(g.contrast));
            }
            EXPECT_EQ(g.background_diff, which.has(Metric::BackgroundDiff) ? a.background_diff : std::nullopt);
        }
        const Metrics ref = metrics_reference(convert<double>(fused), nullptr, which);
        EXPECT_EQ(std::isnan(ref.sharpness), !which.has(Metric::Sharpness));
        EXPECT_EQ(std::isnan(ref.contrast), !which.has(Metric::Contrast));
        if (which.has(Metric::Sharpness)) {
            EXPECT_EQ(ref.sharpness, ref_all.sharpness);
        }
        if (which.has(Metric::Contrast)) {
            EXPECT_EQ(ref.contrast, ref_all.contrast);
        }
    }
}

}  // namespace
}  // namespace vkfuse::test

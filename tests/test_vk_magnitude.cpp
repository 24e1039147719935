// The Vulkan path at every float32 magnitude (issue 11, items 9 and 10): for
// finite inputs from subnormals up to FLT_MAX, every method, rule and metric
// agrees with the double reference within docs/spec.md's tolerance made relative to
// the inputs' magnitude, or throws Error(Numeric); never NaN, Inf, a JSON null
// or a wrong finite number. Small images (29 x 37) keep this file fast.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/rig/background.hpp"

namespace vkfuse::test {
namespace {

constexpr int kH = 29, kW = 37, kC = 3, kK = 3;
constexpr double kTolerance = 1e-5;  // docs/spec.md, for inputs in [0, 1]: here times the magnitude
constexpr float kFltMax = std::numeric_limits<float>::max();
constexpr double kDenormMin = std::numeric_limits<float>::denorm_min();

// From subnormal (1e-44: a few multiples of 2^-149) to FLT_MAX. 1.4e36 is
// where the Laplacian's 256-weight pyrDown sums used to overflow.
const float kScales[] = {1e-44f, 1e-40f, 1e-38f, 1e-30f, 1e30f, 1e36f, 1.4e36f, 1e38f, 3e38f, kFltMax};

// K frames of one scene scaled by a in float32 (what a caller hands over):
// frame 0 structured, frame 1 noise, frame 2 structured with both signs.
std::vector<Image> scene(float a, std::uint32_t seed, int height = kH, int width = kW, int channels = kC) {
    std::vector<Image> out;
    for (int k = 0; k < kK; ++k) {
        const ImageD base = k == 1 ? random_image(height, width, channels, seed + std::uint32_t(k))
                                   : structured_image(height, width, channels, seed + std::uint32_t(k));
        Image f(height, width, channels);
        for (std::size_t i = 0; i < f.data.size(); ++i) {
            const float v = float(base.data[i]);
            f.data[i] = (k == 2 ? 2.0f * v - 1.0f : v) * a;
        }
        out.push_back(f);
    }
    return out;
}

std::vector<ImageD> to_double(const std::vector<Image>& frames) {
    std::vector<ImageD> out;
    for (const Image& f : frames) out.push_back(convert<double>(f));
    return out;
}

double max_abs(const std::vector<double>& values) {
    double m = 0;
    for (double v : values) m = std::max(m, std::abs(v));
    return m;
}

double magnitude(const std::vector<Image>& frames) {
    double m = 0;
    for (const Image& f : frames)
        for (float v : f.data) m = std::max(m, std::abs(double(v)));
    return m;
}

std::string label(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

std::string describe(const FusionSpec& s) {
    return std::string(to_string(s.method)) + " " + std::string(to_string(s.wavelet)) + "/" +
           std::string(to_string(s.mode)) + " L=" + std::to_string(s.effective_levels()) + " base=" +
           std::string(to_string(s.base_rule)) + " detail=" + std::string(to_string(s.detail_rule));
}

bool uses_max_abs(const FusionSpec& s) {
    const bool pyramid = s.method == Method::Laplacian || s.method == Method::Wavelet;
    return pyramid && (s.base_rule == Rule::MaxAbs || s.detail_rule == Rule::MaxAbs);
}

FusionSpec method_spec(Method m) {
    FusionSpec s;
    s.method = m;
    return s;
}

FusionSpec wavelet_spec(Wavelet w, WaveletMode mode) {
    FusionSpec s;
    s.method = Method::Wavelet;
    s.wavelet = w;
    s.mode = mode;
    s.levels = std::min(3, max_wavelet_levels(w, kH, kW));
    return s;
}

std::vector<FusionSpec> every_method() {
    std::vector<FusionSpec> out{method_spec(Method::ChannelSum), method_spec(Method::Brovey),
                                method_spec(Method::Laplacian)};
    for (Wavelet w : {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44})
        for (WaveletMode m : {WaveletMode::Periodization, WaveletMode::Symmetric}) out.push_back(wavelet_spec(w, m));
    return out;
}

// Base mean, detail max: no max-abs near-tie can move a sample, so every
// sample (and the metrics of the fused image) must agree.
FusionSpec tie_free(FusionSpec s) {
    s.base_rule = Rule::Mean;
    s.detail_rule = Rule::Max;
    return s;
}

void expect_metric(double gpu, double ref, const std::string& what) {
    EXPECT_TRUE(std::isfinite(gpu)) << what << ": gpu " << gpu;
    EXPECT_LE(std::abs(gpu - ref), kTolerance * std::abs(ref)) << what << ": gpu " << gpu << " ref " << ref;
}

// Fuses frames (S = frames.size() / kK sensors) on the GPU and compares each
// sensor with the reference. fused() may throw Error(Numeric) only where the
// reference itself leaves float32's range.
void check_fusion(Context& ctx, const FusionSpec& spec, const std::vector<Image>& frames, bool metrics) {
    SCOPED_TRACE(describe(spec));
    const int S = int(frames.size()) / kK;
    PlanConfig cfg;
    cfg.fusion = spec;
    cfg.height = frames[0].height;
    cfg.width = frames[0].width;
    cfg.channels = frames[0].channels;
    cfg.frames = kK;
    cfg.sensors = S;
    cfg.metrics = metrics ? MetricSet{Metric::Sharpness, Metric::Contrast} : MetricSet{};
    Plan plan = run_plan(ctx, cfg, frames);
    for (int s = 0; s < S; ++s) {
        SCOPED_TRACE("sensor " + std::to_string(s));
        const std::vector<Image> mine(frames.begin() + s * kK, frames.begin() + (s + 1) * kK);
        const double scale = magnitude(mine);
        const ImageD ref = fuse_reference(to_double(mine), spec);
        const double tolerance = kTolerance * scale + kDenormMin;
        try {
            const Image& gpu = plan.fused(s);
            std::size_t over = 0;
            double worst = 0;
            for (std::size_t i = 0; i < ref.data.size(); ++i) {
                const double d = std::abs(double(gpu.data[i]) - ref.data[i]);
                if (!(d <= tolerance)) ++over;  // NaN counts
                if (std::isfinite(d)) worst = std::max(worst, d);
            }
            const std::size_t allowed = uses_max_abs(spec) ? std::max<std::size_t>(4, ref.data.size() / 10000) : 0;
            EXPECT_LE(over, allowed) << "samples beyond " << tolerance << " (worst " << worst << ", scale " << scale
                                     << ")";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Numeric) << e.what();
            EXPECT_GE(max_abs(ref.data), double(kFltMax) * (1 - kTolerance))
                << "fused() threw although the reference fits in float32: " << e.what();
        }
        if (metrics) {
            const Metrics want = metrics_reference(ref);
            const Metrics got = plan.metrics(s);
            expect_metric(got.sharpness, want.sharpness, "sharpness");
            expect_metric(got.contrast, want.contrast, "contrast");
        }
    }
}

class VulkanMagnitude : public VulkanTest {};

TEST_F(VulkanMagnitude, EveryMethodAtEveryScale) {
    for (float a : kScales) {
        SCOPED_TRACE("scale " + label(a));
        const std::vector<Image> frames = scene(a, 7);
        for (const FusionSpec& spec : every_method()) {
            // At 1e-44 every input is one of eight multiples of 2^-149: nearly
            // every max-abs decision is an exact tie in float and a rounding
            // in double, so either frame is right (docs/spec.md) and only the
            // tie-free rules can be compared there.
            if (a > 1e-43f) check_fusion(ctx(), spec, frames, false);
            check_fusion(ctx(), tie_free(spec), frames, true);
        }
    }
}

TEST_F(VulkanMagnitude, EveryRulePairAtTheExtremes) {
    const Rule rules[] = {Rule::MaxAbs, Rule::Mean, Rule::Max, Rule::Min};
    for (float a : {1e-39f, 3e38f}) {  // 1e-39: subnormal, yet 2^13 steps apart (no ties of quantisation)
        SCOPED_TRACE("scale " + label(a));
        const std::vector<Image> frames = scene(a, 17);
        for (FusionSpec spec : {method_spec(Method::Laplacian), wavelet_spec(Wavelet::Db2, WaveletMode::Periodization),
                                wavelet_spec(Wavelet::Bior22, WaveletMode::Symmetric)})
            for (Rule b : rules)
                for (Rule d : rules) {
                    spec.base_rule = b;
                    spec.detail_rule = d;
                    check_fusion(ctx(), spec, frames, false);
                }
    }
}

// One plan, two sensors six orders of ten apart at both ends: each sensor's
// results are scaled by its own magnitude.
TEST_F(VulkanMagnitude, SensorsOfOnePlanScaleIndependently) {
    for (auto [a0, a1] : {std::pair{1e38f, 1e-38f}, {1e-44f, 1.0f}, {3e38f, 0.5f}}) {
        SCOPED_TRACE("scales " + label(a0) + " " + label(a1));
        std::vector<Image> frames = scene(a0, 27);
        for (const Image& f : scene(a1, 37)) frames.push_back(f);
        check_fusion(ctx(), tie_free(method_spec(Method::Laplacian)), frames, true);
        check_fusion(ctx(), tie_free(wavelet_spec(Wavelet::Bior44, WaveletMode::Symmetric)), frames, true);
        check_fusion(ctx(), method_spec(Method::Brovey), frames, true);
    }
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
    const FrameView view = FrameView::of(image);
    plan.run(std::span(&view, 1));
    return plan.metrics(0);
}

// What `vkfuse metrics --backend vulkan` computes: sharpness, contrast and
// the difference with a background of the same magnitude.
TEST_F(VulkanMagnitude, MetricsAtEveryScale) {
    for (int channels : {1, 3})
        for (float a : kScales) {
            SCOPED_TRACE("scale " + label(a) + " C=" + std::to_string(channels));
            const std::vector<Image> f = scene(a, 47, kH, kW, channels);
            const ImageD image = convert<double>(f[0]), background = convert<double>(f[2]);
            const Metrics want = metrics_reference(image, &background);
            const Metrics got = gpu_metrics(ctx(), f[0], &f[2]);
            expect_metric(got.sharpness, want.sharpness, "sharpness");
            expect_metric(got.contrast, want.contrast, "contrast");
            ASSERT_TRUE(got.background_diff.has_value());
            expect_metric(*got.background_diff, *want.background_diff, "background_diff");
        }
}

// A frame and a background of very different magnitudes share one scale on
// the device: where both fit, every metric agrees; where they lie too far
// apart for float32 to hold both, the plan says so.
TEST_F(VulkanMagnitude, BackgroundOfAnotherMagnitude) {
    // Frames far below their background reach the kernels near 2^-64 where
    // the device keeps subnormals, near 2^-40 where it may flush them
    // (DeviceInfo::float32_subnormals): one scale then holds a narrower range.
    const double widest = ctx().device().float32_subnormals ? 1e37 : 1e30;
    for (auto [a, b] : {std::pair{1e-30f, 1e10f}, {1e30f, 1e-30f}, {3e38f, 1.0f}, {1e-40f, 1e-10f}, {1e-44f, 1e30f},
                        {1e-35f, 1e-3f}}) {
        SCOPED_TRACE("frame " + label(a) + " background " + label(b));
        const Image frame = scene(a, 57)[0], background = scene(b, 67)[1];
        const ImageD image = convert<double>(frame), bg = convert<double>(background);
        const Metrics want = metrics_reference(image, &bg);
        try {
            const Metrics got = gpu_metrics(ctx(), frame, &background);
            expect_metric(got.sharpness, want.sharpness, "sharpness");
            expect_metric(got.contrast, want.contrast, "contrast");
            ASSERT_TRUE(got.background_diff.has_value());
            expect_metric(*got.background_diff, *want.background_diff, "background_diff");
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Numeric) << e.what();
            // One scale holds values within 2^124 of each other (2^100 where
            // the device may flush subnormals; vk/engine/magnitude.hpp).
            EXPECT_GT(double(b) / double(a), widest) << e.what();
        }
    }
}

// Brovey's dark branch (s < 1e-6, docs/spec.md) is an absolute threshold, the one
// thing that does not scale. Pixels whose positive sum lies just below and
// just above it must take the reference's branch while a huge (or tiny)
// pixel elsewhere sets the image's scale. Checked per pixel, relative to that
// pixel's own inputs, since a wrong branch is tiny next to the huge pixel.
TEST_F(VulkanMagnitude, BroveyThresholdHoldsAtEveryScale) {
    // (positive parts sum to 0.95e-6: the mean; 1.05e-6: the weighted sum)
    const float straddle[][3] = {{0.5e-6f, 0.45e-6f, -3e-6f}, {0.5e-6f, 0.55e-6f, -3e-6f},
                                 {0.3e-6f, 0.6e-6f, -1e-6f},  {0.3e-6f, 0.75e-6f, -1e-6f},
                                 {0.99e-6f, 0.0f, -2e-6f},     {1.01e-6f, 0.0f, -2e-6f}};
    for (float big : {3e38f, kFltMax, 1e37f, 1e20f, 0.0f}) {
        SCOPED_TRACE("largest pixel " + label(big));
        std::vector<Image> frames(kK, Image(5, 7, 1));
        for (int k = 0; k < kK; ++k) {
            for (std::size_t i = 0; i < frames[std::size_t(k)].data.size(); ++i)
                frames[std::size_t(k)].data[i] = straddle[i % 6][k] * (i % 12 < 6 ? 1.0f : 1.5f);
            frames[std::size_t(k)].data[17] = big;
        }
        const ImageD ref = fuse_reference(to_double(frames), method_spec(Method::Brovey));
        PlanConfig cfg;
        cfg.fusion = method_spec(Method::Brovey);
        cfg.height = 5;
        cfg.width = 7;
        cfg.channels = 1;
        cfg.frames = kK;
        Plan plan = run_plan(ctx(), cfg, frames);
        const Image& gpu = plan.fused(0);
        for (std::size_t i = 0; i < ref.data.size(); ++i) {
            double own = 0;
            for (const Image& f : frames) own = std::max(own, std::abs(double(f.data[i])));
            EXPECT_LE(std::abs(double(gpu.data[i]) - ref.data[i]), kTolerance * own)
                << "pixel " << i << ": gpu " << gpu.data[i] << " ref " << ref.data[i];
        }
    }
    // Tiny frames: every positive sum is far below 1e-6, so the reference takes
    // the mean everywhere; scaled up on the device they must not take the
    // weighted branch.
    for (float tiny : {1e-44f, 1e-39f, 1e-20f}) {
        SCOPED_TRACE("scale " + label(tiny));
        const std::vector<Image> frames = scene(tiny, 77, 5, 7, 1);
        const ImageD ref = fuse_reference(to_double(frames), method_spec(Method::Brovey));
        PlanConfig cfg;
        cfg.fusion = method_spec(Method::Brovey);
        cfg.height = 5;
        cfg.width = 7;
        cfg.channels = 1;
        cfg.frames = kK;
        Plan plan = run_plan(ctx(), cfg, frames);
        const Image& gpu = plan.fused(0);
        for (std::size_t i = 0; i < ref.data.size(); ++i)
            EXPECT_LE(std::abs(double(gpu.data[i]) - ref.data[i]), kTolerance * tiny + kDenormMin)
                << "pixel " << i << ": gpu " << gpu.data[i] << " ref " << ref.data[i];
    }
}

// A fused value beyond FLT_MAX cannot be handed back as float32: fused()
// says so (the metrics, in double, still can be read). Checked against the
// reference, which must indeed leave float32's range there.
TEST_F(VulkanMagnitude, ResultBeyondFloatRangeIsANumericError) {
    std::vector<Image> frames(2, Image(8, 8, 1));
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            frames[0].at(y, x, 0) = x < 4 ? kFltMax : 0.0f;
            frames[1].at(y, x, 0) = x < 4 ? 0.0f : kFltMax;
        }
    FusionSpec spec = method_spec(Method::Laplacian);
    spec.levels = 2;
    spec.base_rule = Rule::Max;
    spec.detail_rule = Rule::Max;
    const ImageD ref = fuse_reference(to_double(frames), spec);
    ASSERT_GT(max_abs(ref.data), double(kFltMax));
    PlanConfig cfg;
    cfg.fusion = spec;
    cfg.height = 8;
    cfg.width = 8;
    cfg.channels = 1;
    cfg.frames = 2;
    Plan plan = run_plan(ctx(), cfg, frames);
    expect_error([&] { (void)plan.fused(0); }, "sensor 0", ErrorKind::Numeric, "float32");
    const Metrics want = metrics_reference(ref);
    expect_metric(plan.metrics(0).sharpness, want.sharpness, "sharpness");
    expect_metric(plan.metrics(0).contrast, want.contrast, "contrast");
}

// NaN or Inf in a frame is bad input (docs/spec.md), as for the reference: the
// plan names the frame instead of fusing it (a max-abs rule would silently
// skip a NaN).
TEST_F(VulkanMagnitude, NonFiniteFrameIsANumericError) {
    std::vector<Image> frames = scene(1.0f, 87);
    frames[1].at(3, 5, 2) = std::numeric_limits<float>::quiet_NaN();
    PlanConfig cfg;
    cfg.fusion = method_spec(Method::Laplacian);
    cfg.height = kH;
    cfg.width = kW;
    cfg.channels = kC;
    cfg.frames = kK;
    Plan plan(ctx(), cfg);
    std::vector<FrameView> views;
    for (const Image& f : frames) views.push_back(FrameView::of(f));
    expect_error([&] { plan.run(views); }, "frame 1 of sensor 0", ErrorKind::Numeric, "NaN at row 3, column 5, channel 2");
    frames[1].at(3, 5, 2) = -std::numeric_limits<float>::infinity();
    expect_error([&] { plan.run(views); }, "frame 1 of sensor 0", ErrorKind::Numeric, "-Inf at row 3, column 5");
}

// The background model's mean (a plan kind of its own, F32 frames) at the extremes.
TEST_F(VulkanMagnitude, MeanAtTheExtremes) {
    for (float a : {1e-44f, 3e38f, kFltMax}) {
        SCOPED_TRACE("scale " + label(a));
        const std::vector<Image> frames = scene(a, 97);
        std::vector<FrameView> views;
        for (const Image& f : frames) views.push_back(FrameView::of(f));
        BackgroundModel model(ctx(), kH, kW, kC, int(frames.size()), PixelType::F32);
        const Image gpu = model.mean(views);
        const ImageD ref = background_mean_reference(views);
        const double tolerance = kTolerance * magnitude(frames) + kDenormMin;
        std::size_t over = 0;
        for (std::size_t i = 0; i < ref.data.size(); ++i) over += !(std::abs(double(gpu.data[i]) - ref.data[i]) <= tolerance);
        EXPECT_EQ(over, 0u) << "samples beyond " << tolerance;
    }
}

// float16 planes: a value past 65504 is still reported (plan.hpp), and frames
// far beyond it are brought into range like float32 ones.
TEST_F(VulkanMagnitude, Fp16StorageAtTheExtremes) {
    if (!ctx().device().fp16_storage) GTEST_SKIP() << ctx().device().name << " has no 16-bit storage";
    PlanConfig cfg;
    cfg.fusion = tie_free(method_spec(Method::Laplacian));
    cfg.height = kH;
    cfg.width = kW;
    cfg.channels = kC;
    cfg.frames = kK;
    cfg.precision = Precision::Fp16Storage;
    Plan overflow = run_plan(ctx(), cfg, scene(1e6f, 107));
    expect_error([&] { (void)overflow.fused(0); }, "sensor 0", ErrorKind::Numeric, "float16's range");
    expect_error([&] { (void)overflow.metrics(0); }, "sensor 0", ErrorKind::Numeric, "float16's range");
    for (float a : {1e-44f, 1e38f, kFltMax}) {
        SCOPED_TRACE("scale " + label(a));
        const std::vector<Image> frames = scene(a, 107);
        Plan plan = run_plan(ctx(), cfg, frames);
        const ImageD ref = fuse_reference(to_double(frames), cfg.fusion);
        const double scale = magnitude(frames);
        constexpr double kFp16Tolerance = 3e-3;  // float16 rounding (test_vk_fp16_storage.cpp)
        try {
            double worst = 0;
            for (std::size_t i = 0; i < ref.data.size(); ++i)
                worst = std::max(worst, std::abs(double(plan.fused(0).data[i]) - ref.data[i]));
            EXPECT_LE(worst, kFp16Tolerance * scale + kDenormMin);
        } catch (const Error& e) {  // float16's rounding may carry a value near FLT_MAX past it
            EXPECT_EQ(e.kind(), ErrorKind::Numeric) << e.what();
            EXPECT_GE(max_abs(ref.data), double(kFltMax) * (1 - kFp16Tolerance)) << e.what();
        }
        const Metrics want = metrics_reference(ref);
        EXPECT_LE(std::abs(plan.metrics(0).sharpness - want.sharpness), 2e-4 * want.sharpness);
        EXPECT_LE(std::abs(plan.metrics(0).contrast - want.contrast), 2e-4 * want.contrast);
    }
}

}  // namespace
}  // namespace vkfuse::test

// Fusing K identical frames is the identity in exact arithmetic. In float32
// every pass adds rounding, and a systematic part would compound when the
// output is fed back as input, as a rig re-fusing its own results would do.
// 100 passes, at the default and at the deepest level count (Laplacian down
// to 1 x 1, max_wavelet_levels for each wavelet).
//
// Measured on lavapipe, 96 x 150 (worst over K = 2 max-abs and K = 3 mean):
//   Laplacian                            <= 7.2e-7
//   wavelet, periodization  haar 3.0e-7, bior2.2 2.0e-6, db2 7.6e-6, bior4.4 9.0e-6
//   wavelet, symmetric      haar 1.6e-6, bior2.2 1.4e-6, db2 4.0e-6, bior4.4 8.1e-6
// A nearly unchanged image fed back meets the same roundings every pass, so
// the drift grows linearly. Two things keep it under 1e-5 after 100 passes:
// the periodization kernels drop pywt's sqrt(2) from the taps where that
// reconstructs closer to exactly in float (graph_wavelet.cpp, analysis_scale:
// haar's and bior2.2's taps become exact; 3.3e-5 and 4.1e-5 before), and
// every filter output and every lifting step is a dot product rounded once
// (compensated.glsl; periodization bior4.4 1.5e-5 and symmetric bior4.4
// 1.01e-5 with plain float sums). The wavelets run in every filter arithmetic
// the device offers. Any compounding (growth faster than linear) fails every
// case.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "stress_support.hpp"
#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::test {
namespace {

constexpr int kPasses = 100;
constexpr double kDrift = 1e-5;
constexpr int kHeight = 96, kWidth = 150;  // odd halvings: 150 -> 75 -> 38

// The mean rule divides a sum of K equal values by K, which float rounds
// for K = 3: the case where a biased rounding would add up over passes.
FusionSpec with_mean_rules(FusionSpec s) {
    s.base_rule = Rule::Mean;
    s.detail_rule = Rule::Mean;
    return s;
}

// Default and deepest level count of one method/mode, with K = 2 (spec's
// rules) at both and K = 3 (mean rules) at the default.
struct FeedbackRun {
    FusionSpec spec;
    int frames;
};

std::vector<FeedbackRun> runs_of(const FusionSpec& default_levels, const FusionSpec& deepest) {
    return {{default_levels, 2}, {deepest, 2}, {with_mean_rules(default_levels), 3}};
}

std::vector<FeedbackRun> wavelet_runs(WaveletMode mode) {
    std::vector<FeedbackRun> runs;
    for (Wavelet w : kAllWavelets)
        for (const FeedbackRun& r : runs_of(wavelet_spec(w, mode, 3), wavelet_spec(w, mode, max_wavelet_levels(w, kHeight, kWidth))))
            runs.push_back(r);
    return runs;
}

class StressFeedback : public VulkanTest {
protected:
    void feed_back(const std::vector<FeedbackRun>& runs, double bound, const std::vector<Context*>& contexts) {
        const Image first = structured_frame(kHeight, kWidth, 1, 17);
        for (Context* context : contexts)
        for (const auto& [spec, K] : runs) {
            std::string what = "gpu feedback " + describe(spec) + " K=" + std::to_string(K);
            if (spec.method == Method::Wavelet) what += ", " + std::string(to_string(context->filter_arithmetic()));
            SCOPED_TRACE(what);
            PlanConfig cfg{spec, kHeight, kWidth, 1, K, 1};
            cfg.metrics = {};
            Plan plan(*context, cfg);
            Image current = first;
            double drift_at_10 = 0;
            for (int pass = 1; pass <= kPasses; ++pass) {
                std::vector<FrameView> views(std::size_t(K), FrameView::of(current));
                plan.run(views);
                current = plan.fused(0);
                if (pass == 10) drift_at_10 = max_abs_diff(current, convert<double>(first));
            }
            const double drift = max_abs_diff(current, convert<double>(first));
            EXPECT_LE(drift, bound);
            // Linear growth gives 10x from pass 10 to 100, rounding noise ~3x; compounding more.
            EXPECT_LE(drift, 12 * drift_at_10 + 1e-7) << "after 10 passes: " << drift_at_10;
            report(what, drift);
        }
    }
};

TEST_F(StressFeedback, LaplacianDownToOnePixel) {
    feed_back(runs_of(method_spec(Method::Laplacian), method_spec(Method::Laplacian, levels_to_one_pixel(kHeight, kWidth))), kDrift,
              {&ctx()});
}

TEST_F(StressFeedback, EveryWaveletPeriodization) {
    feed_back(wavelet_runs(WaveletMode::Periodization), kDrift, filter_arithmetic_contexts());
}

TEST_F(StressFeedback, EveryWaveletSymmetric) {
    feed_back(wavelet_runs(WaveletMode::Symmetric), kDrift, filter_arithmetic_contexts());
}

// The double reference: pywt's bior4.4 taps, as published to 16 digits, are
// biorthogonal only to ~1e-12, which 100 passes add up to 1.5e-10; every other
// filter bank stays below 2e-13. Anything near float's drift would be a bug.
TEST(StressFeedbackCpu, HundredPassesOnTheCpuDoNotDrift) {
    const ImageD first = structured_image(kHeight / 2, kWidth / 2, 1, 18);
    std::vector<FusionSpec> specs{method_spec(Method::Laplacian, levels_to_one_pixel(first.height, first.width))};
    for (Wavelet w : kAllWavelets)
        for (WaveletMode m : kAllModes) specs.push_back(wavelet_spec(w, m, max_wavelet_levels(w, first.height, first.width)));
    for (const FusionSpec& spec : specs) {
        SCOPED_TRACE(describe(spec));
        std::vector<ImageD> frames(2, first);
        for (int pass = 0; pass < kPasses; ++pass) frames.assign(2, fuse_reference(frames, spec));
        const double drift = max_abs_diff(frames[0], first);
        EXPECT_LE(drift, 1e-9);
        report("cpu feedback " + describe(spec), drift);
    }
}

}  // namespace
}  // namespace vkfuse::test

// Skipping plans (PlanConfig::skip): the device's change scores against the
// CPU twin, idle sensors' results, and fused sensors exactly as a plan that
// skips nothing fuses them, whatever slot they were compacted into.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/method_table.hpp"
#include "expect_error.hpp"
#include "skip_scene.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

// Small frames carry few wavelet levels.
FusionSpec haar() {
    FusionSpec spec;
    spec.wavelet = Wavelet::Haar;
    spec.levels = 2;
    return spec;
}

class VulkanSkip : public VulkanTest {};

// The largest tile score and the share of tiles over a threshold, against
// the double-precision reference, with rows of whole quads and without.
TEST_F(VulkanSkip, ScoresMatchTheReference) {
    for (auto [h, w] : {std::pair{64, 96}, std::pair{75, 83}}) {
        const Scene scene = make_scene(h, w, 3, 2, 7);
        const std::vector<std::vector<Bytes>> sensors = {frames_of(scene, 1, 4.0, false), frames_of(scene, 2, 4.0, true)};
        for (int s = 0; s < 2; ++s) {
            const std::vector<FrameView> all = views(scene, sensors);
            const std::vector<double> ref =
                change_scores_reference(std::span(all).subspan(std::size_t(s) * 2, 2), scene.reference);
            // A threshold between two scores, far from both: the count is exact.
            std::vector<double> sorted = ref;
            std::sort(sorted.begin(), sorted.end());
            const double threshold = (sorted[sorted.size() / 2] + sorted[sorted.size() / 2 + 1]) / 2;
            ASSERT_GT(sorted[sorted.size() / 2 + 1] - sorted[sorted.size() / 2], 1e-4) << "pick another seed";
            Plan plan(ctx(), skip_config(scene, 2, haar(), SkipPolicy::Idle, threshold));
            for (int t = 0; t < 2; ++t) {
                plan.set_skip_reference(t, scene.reference);
                plan.set_background(t, FrameView::of(scene.reference.mean[0]));
            }
            plan.run(all);
            const SkipOutcome o = plan.skip_outcome(s);
            EXPECT_NEAR(o.score, sorted.back(), 1e-5 * sorted.back()) << h << "x" << w << " sensor " << s;
            const auto over = std::count_if(ref.begin(), ref.end(), [&](double v) { return v > threshold; });
            EXPECT_DOUBLE_EQ(o.changed_fraction, double(over) / double(ref.size())) << h << "x" << w << " sensor " << s;
            EXPECT_FALSE(o.idle);
        }
    }
}

// Three sensors, one pressed: the pressed one is fused exactly as a plan
// that skips nothing fuses it (from slot 0, not its own slot 1), the
// others return the fused reference and its metrics. Then the press moves
// to sensor 2 while sensor 1 goes idle. Every method's row at its defaults.
TEST_F(VulkanSkip, IdleSensorsReturnTheFusedReferenceAndPressedOnesFuseExactly) {
    const Scene scene = make_scene(96, 128, 3, 3, 11);
    const Image background = convert<float>(fuse_reference(
        std::vector<ImageD>{convert<double>(scene.reference.mean[0]), convert<double>(scene.reference.mean[1]),
                            convert<double>(scene.reference.mean[2])},
        FusionSpec{}));
    for (const core::MethodInfo& row : core::method_table()) {
        FusionSpec spec;
        spec.method = row.method;
        Plan skipping(ctx(), skip_config(scene, 3, spec, SkipPolicy::Idle, 8.0));
        Plan full(ctx(), skip_config(scene, 3, spec, SkipPolicy::Off, 8.0));
        for (int s = 0; s < 3; ++s) {
            skipping.set_skip_reference(s, scene.reference);
            skipping.set_background(s, FrameView::of(background));
            full.set_background(s, FrameView::of(background));
        }
        std::vector<ImageD> means;
        for (const Image& m : scene.reference.mean) means.push_back(convert<double>(m));
        const ImageD fused_reference = fuse_reference(means, spec);
        for (int pressed : {1, 2}) {
            std::vector<std::vector<Bytes>> sensors;
            for (int s = 0; s < 3; ++s) sensors.push_back(frames_of(scene, std::uint32_t(10 * pressed + s), 3.0, s == pressed));
            const std::vector<FrameView> all = views(scene, sensors);
            const std::uint64_t before = skipping.submits();
            skipping.run(all);
            full.run(all);
            EXPECT_EQ(skipping.submits(), before + 1);
            for (int s = 0; s < 3; ++s) {
                const std::string where = std::string(row.name) + " sensor " + std::to_string(s);
                const SkipOutcome o = skipping.skip_outcome(s);
                EXPECT_EQ(o.idle, s != pressed) << where << " score " << o.score;
                if (s == pressed) {
                    EXPECT_EQ(o.fused_fraction, 1.0) << where;
                    EXPECT_EQ(skipping.fused(s).data, full.fused(s).data) << where;
                    EXPECT_EQ(skipping.metrics(s).sharpness, full.metrics(s).sharpness) << where;
                    EXPECT_EQ(skipping.metrics(s).background_diff, full.metrics(s).background_diff) << where;
                    continue;
                }
                EXPECT_EQ(o.fused_fraction, 0.0) << where;
                EXPECT_EQ(skipping.fused(s).data, convert<float>(fused_reference).data) << where;
                // Its metrics: those of that image, against the background that was set.
                const Metrics m = skipping.metrics(s);
                const ImageD background_d = convert<double>(background);
                const Metrics expected = metrics_reference(convert<double>(convert<float>(fused_reference)), &background_d);
                EXPECT_EQ(m.sharpness, expected.sharpness) << where;
                EXPECT_EQ(m.contrast, expected.contrast) << where;
                ASSERT_TRUE(m.background_diff) << where;
                EXPECT_EQ(*m.background_diff, *expected.background_diff) << where;
            }
        }
    }
}

// SkipPolicy::Static: a sensor whose frames match its last fused cycle's
// (within noise) reuses that result, bit for bit; one whose press moved is
// fused again, exactly as a plan that skips nothing fuses it.
void static_reuse(Context& context) {
    const Scene scene = make_scene(64, 96, 3, 2, 21);
    Plan plan(context, skip_config(scene, 2, haar(), SkipPolicy::Static, 8.0));
    Plan full(context, skip_config(scene, 2, haar(), SkipPolicy::Off, 8.0));
    for (int s = 0; s < 2; ++s) {
        plan.set_skip_reference(s, scene.reference);
        plan.set_background(s, FrameView::of(scene.reference.mean[0]));
        full.set_background(s, FrameView::of(scene.reference.mean[0]));
    }
    // Sensor 1 pressed in every run; its noise changes, its press does not
    // until run 3, where a bright stripe appears.
    std::vector<Image> first_result;
    Metrics first_metrics;
    for (int run = 0; run < 4; ++run) {
        std::vector<std::vector<Bytes>> sensors = {frames_of(scene, std::uint32_t(100 + run), 2.0, false),
                                                   frames_of(scene, std::uint32_t(200 + run), 2.0, true)};
        if (run == 3)
            for (Bytes& f : sensors[1])
                for (int x = 0; x < 96 * 3; ++x) f[std::size_t(5 * 96 * 3 + x)] = 250;
        const std::vector<FrameView> all = views(scene, sensors);
        plan.run(all);
        full.run(all);
        EXPECT_TRUE(plan.skip_outcome(0).idle) << "run " << run;
        const SkipOutcome o = plan.skip_outcome(1);
        EXPECT_FALSE(o.idle) << "run " << run;
        EXPECT_EQ(o.reused, run == 1 || run == 2) << "run " << run;
        EXPECT_EQ(o.fused_fraction, o.reused ? 0.0 : 1.0) << "run " << run;
        if (run == 0) {
            first_result = {plan.fused(1)};
            first_metrics = plan.metrics(1);
        }
        if (o.reused) {
            EXPECT_EQ(plan.fused(1).data, first_result[0].data) << "run " << run;
            EXPECT_EQ(plan.metrics(1).sharpness, first_metrics.sharpness) << "run " << run;
            EXPECT_EQ(plan.metrics(1).background_diff, first_metrics.background_diff) << "run " << run;
            EXPECT_NE(full.fused(1).data, first_result[0].data) << "run " << run;  // the noise did change
        } else {
            EXPECT_EQ(plan.fused(1).data, full.fused(1).data) << "run " << run;
            EXPECT_EQ(plan.metrics(1).contrast, full.metrics(1).contrast) << "run " << run;
        }
    }
    EXPECT_EQ(plan.submits(), 2u);  // runs 0 and 3
}

// The same through device addresses (plans beyond maxStorageBufferRange):
// the detection and the indirect dispatches in the kernels' "_addr" variants.
TEST_F(VulkanSkip, StaticSensorsReuseTheirLastFusedResult) {
    static_reuse(ctx());
    SKIP_WITHOUT_DEVICE_ADDRESSES();
    static_reuse(addressed_context());
}

// A cycle in which nothing changed submits no fusion at all.
TEST_F(VulkanSkip, AllIdleSubmitsNoFusion) {
    const Scene scene = make_scene(32, 40, 3, 2, 5);
    Plan plan(ctx(), skip_config(scene, 2, haar(), SkipPolicy::Idle, 8.0));
    for (int s = 0; s < 2; ++s) {
        plan.set_skip_reference(s, scene.reference);
        plan.set_background(s, FrameView::of(scene.reference.mean[0]));
    }
    const std::vector<std::vector<Bytes>> sensors = {frames_of(scene, 3, 2.0, false), frames_of(scene, 4, 2.0, false)};
    plan.run(views(scene, sensors));
    EXPECT_EQ(plan.submits(), 0u);
    for (int s = 0; s < 2; ++s) {
        EXPECT_TRUE(plan.skip_outcome(s).idle);
        EXPECT_EQ(plan.skip_outcome(s).changed_fraction, 0.0);
        EXPECT_LT(plan.skip_outcome(s).score, 8.0);
    }
}

// "Changed" is strict: over a noiseless background (every tile's noise the
// floor, half an 8-bit step) a sample 4 levels off scores exactly 8, which
// a threshold of 8 keeps idle, and one level further is fused; the CPU twin
// scores the same. Both sensors sit in one plan, in different tiles.
TEST_F(VulkanSkip, AScoreEqualToTheThresholdStaysIdle) {
    Scene scene{64, 96, 3, 2, {}};
    for (int k = 0; k < scene.k; ++k) {
        Image mean(scene.h, scene.w, scene.c), deviation(scene.h, scene.w, scene.c);
        std::fill(mean.data.begin(), mean.data.end(), float(100 + 20 * k) / 255.0f);
        scene.reference.mean.push_back(std::move(mean));
        scene.reference.deviation.push_back(std::move(deviation));
    }
    const std::vector<Bytes> still = frames_of(scene, 1, 0.0, false);
    std::vector<std::vector<Bytes>> sensors{still, still};
    sensors[0][1][(std::size_t(40) * scene.w + 70) * 3 + 2] += 4;  // exactly at the threshold
    sensors[1][0][(std::size_t(10) * scene.w + 5) * 3 + 1] += 5;   // one level above it
    const std::vector<FrameView> all = views(scene, sensors);
    for (int s = 0; s < 2; ++s) {
        const std::vector<double> ref =
            change_scores_reference(std::span(all).subspan(std::size_t(s) * 2, 2), scene.reference);
        EXPECT_EQ(*std::max_element(ref.begin(), ref.end()), s == 0 ? 8.0 : 10.0) << "sensor " << s;
    }
    Plan plan(ctx(), skip_config(scene, 2, haar(), SkipPolicy::Idle, 8.0));
    for (int s = 0; s < 2; ++s) {
        plan.set_skip_reference(s, scene.reference);
        plan.set_background(s, FrameView::of(scene.reference.mean[0]));
    }
    plan.run(all);
    EXPECT_EQ(plan.skip_outcome(0).score, 8.0);
    EXPECT_TRUE(plan.skip_outcome(0).idle);
    EXPECT_EQ(plan.skip_outcome(0).changed_fraction, 0.0);
    EXPECT_EQ(plan.skip_outcome(1).score, 10.0);
    EXPECT_FALSE(plan.skip_outcome(1).idle);
}

TEST_F(VulkanSkip, BadConfigurationAndReferencesAreRefused) {
    const Scene scene = make_scene(16, 24, 3, 2, 3);
    PlanConfig f32 = skip_config(scene, 1, haar(), SkipPolicy::Idle, 8.0);
    f32.input = PixelType::F32;
    expect_error([&] { Plan p(ctx(), f32); }, "plan", ErrorKind::InvalidArgument, "8-bit frames");
    PlanConfig bad = skip_config(scene, 1, haar(), SkipPolicy::Idle, std::nan(""));
    expect_error([&] { Plan p(ctx(), bad); }, "plan", ErrorKind::InvalidArgument, "threshold");
    Plan plan(ctx(), skip_config(scene, 1, haar(), SkipPolicy::Idle, 8.0));
    plan.set_background(0, FrameView::of(scene.reference.mean[0]));
    const std::vector<std::vector<Bytes>> sensors = {frames_of(scene, 1, 1.0, false)};
    expect_error([&] { plan.run(views(scene, sensors)); }, "plan run", ErrorKind::InvalidArgument,
                 "no skip reference set for sensor 0");
    SkipReference short_ref = scene.reference;
    short_ref.mean.pop_back();
    expect_error([&] { plan.set_skip_reference(0, short_ref); }, "skip reference of sensor 0",
                 ErrorKind::InvalidArgument, "1 means and 2 deviations for 2 frames");
    SkipReference nan_ref = scene.reference;
    nan_ref.deviation[1].data[5] = std::nanf("");
    expect_error([&] { plan.set_skip_reference(0, nan_ref); }, "skip reference of sensor 0", ErrorKind::Numeric,
                 "NaN or Inf");
    Plan unskipping(ctx(), skip_config(scene, 1, haar(), SkipPolicy::Off, 8.0));
    expect_error([&] { unskipping.set_skip_reference(0, scene.reference); }, "plan", ErrorKind::InvalidArgument,
                 "skip off");
}

}  // namespace
}  // namespace vkfuse::test

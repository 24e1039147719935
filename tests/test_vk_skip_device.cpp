// Skipping decided on the device (SkipPolicy::Idle, vk/plan/plan_skip.hpp): the
// decision, the frames and backgrounds moved into their slots and the
// indirect dispatches all happen inside the cycle's one submit. Pressed
// sensors come and go across six sensors, so fused sensors move into slots
// other than their own, slots change sensors and backgrounds change between
// cycles; every fused sensor must match a plan that skips nothing, bit for
// bit, and every idle one return its fused reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "skip_scene.hpp"
#include "vk/plan/plan_skip.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

class VulkanSkipDevice : public VulkanTest {};

FusionSpec haar() {
    FusionSpec spec;
    spec.wavelet = Wavelet::Haar;
    spec.levels = 2;
    return spec;
}

// A background per sensor, each different: a slot given another sensor's
// background would change background_diff.
Image background_of(const Scene& scene, int sensor) {
    Image b = scene.reference.mean[std::size_t(sensor) % scene.reference.mean.size()];
    for (float& v : b.data) v = std::clamp(v + 0.01f * float(sensor), 0.0f, 1.0f);
    return b;
}

// One cycle: the sensors in `pressed` pressed, the rest still.
struct Cycle {
    std::set<int> pressed;
    int new_background = -1;  // a sensor whose background changes before the cycle
};

void presses_come_and_go(Context& context, const Scene& scene, const FusionSpec& spec, bool expect_on_device) {
    constexpr int S = 6;
    const PlanConfig config = skip_config(scene, S, spec, SkipPolicy::Idle, 8.0);
    ASSERT_EQ(vk::skip_decides_on_device(config), expect_on_device) << scene.h << "x" << scene.w << " K " << scene.k;
    Plan skipping(context, config);
    Plan full(context, skip_config(scene, S, spec, SkipPolicy::Off, 8.0));
    std::vector<Image> backgrounds;
    for (int s = 0; s < S; ++s) {
        backgrounds.push_back(background_of(scene, s));
        skipping.set_skip_reference(s, scene.reference);
        skipping.set_background(s, FrameView::of(backgrounds.back()));
        full.set_background(s, FrameView::of(backgrounds.back()));
    }
    std::vector<ImageD> means;
    for (const Image& m : scene.reference.mean) means.push_back(convert<double>(m));
    const Image fused_reference = convert<float>(fuse_reference(means, spec));
    // Sensor 5 fuses alone in slot 0 twice, its background changed between:
    // the same sensor in the same slot must still take the new one.
    const std::vector<Cycle> cycles = {{{1, 4}}, {{0, 2, 3, 5}}, {{}}, {{5}}, {{5}, 5},
                                       {{0, 1, 2, 3, 4, 5}}, {{3}, 0}, {{0, 4}}, {{2, 5}, 2}};
    std::uint64_t fusing_cycles = 0;
    for (std::size_t c = 0; c < cycles.size(); ++c) {
        const Cycle& cycle = cycles[c];
        if (cycle.new_background >= 0) {
            Image& b = backgrounds[std::size_t(cycle.new_background)];
            for (float& v : b.data) v = 1.0f - v;
            skipping.set_background(cycle.new_background, FrameView::of(b));
            full.set_background(cycle.new_background, FrameView::of(b));
        }
        std::vector<std::vector<Bytes>> sensors;
        for (int s = 0; s < S; ++s)
            sensors.push_back(frames_of(scene, std::uint32_t(100 * c + s), 2.0, cycle.pressed.count(s) > 0));
        const std::vector<FrameView> all = views(scene, sensors);
        skipping.run(all);
        full.run(all);
        fusing_cycles += !cycle.pressed.empty();
        EXPECT_EQ(skipping.submits(), fusing_cycles) << "cycle " << c;
        for (int s = 0; s < S; ++s) {
            const std::string where = "cycle " + std::to_string(c) + " sensor " + std::to_string(s);
            const bool pressed = cycle.pressed.count(s) > 0;
            EXPECT_EQ(skipping.skip_outcome(s).idle, !pressed) << where;
            const Image& expected = pressed ? full.fused(s) : fused_reference;
            EXPECT_EQ(skipping.fused(s).data, expected.data) << where;
            if (!pressed) continue;
            const Metrics got = skipping.metrics(s), want = full.metrics(s);
            EXPECT_EQ(got.sharpness, want.sharpness) << where;
            EXPECT_EQ(got.contrast, want.contrast) << where;
            ASSERT_TRUE(got.background_diff) << where;
            EXPECT_EQ(*got.background_diff, *want.background_diff) << where;
        }
    }
}

TEST_F(VulkanSkipDevice, PressesComingAndGoingFuseAsAPlanThatSkipsNothing) {
    presses_come_and_go(ctx(), make_scene(64, 96, 3, 3, 31), haar(), true);
    FusionSpec brovey;
    brovey.method = Method::Brovey;
    presses_come_and_go(ctx(), make_scene(64, 96, 3, 3, 32), brovey, true);
}

// Sensors whose frames do not start on word boundaries (75 x 83 x 3 x 2
// bytes) are moved by the host, which decides for them, with the same results.
TEST_F(VulkanSkipDevice, FramesOffWordBoundariesAreDecidedOnTheHost) {
    presses_come_and_go(ctx(), make_scene(75, 83, 3, 2, 33), haar(), false);
}

// The same through device addresses: the decision's and the gathers' "_addr" variants.
TEST_F(VulkanSkipDevice, DeviceAddressesToo) {
    SKIP_WITHOUT_DEVICE_ADDRESSES();
    presses_come_and_go(addressed_context(), make_scene(64, 96, 3, 3, 34), haar(), true);
}

// One round trip: the detection and the compaction are stages of the
// cycle's own command buffer, before the fusion's; a plan whose host
// decides (Static) detects in a submit of its own, which its profile lacks.
TEST_F(VulkanSkipDevice, DetectionAndCompactionRunInTheCyclesOneSubmit) {
    const Scene scene = make_scene(64, 96, 3, 3, 35);
    for (SkipPolicy policy : {SkipPolicy::Idle, SkipPolicy::Static}) {
        PlanConfig config = skip_config(scene, 2, haar(), policy, 8.0);
        config.profile = true;
        Plan plan(ctx(), config);
        for (int s = 0; s < 2; ++s) {
            plan.set_skip_reference(s, scene.reference);
            plan.set_background(s, FrameView::of(scene.reference.mean[0]));
        }
        const std::vector<std::vector<Bytes>> sensors = {frames_of(scene, 1, 2.0, false), frames_of(scene, 2, 2.0, true)};
        plan.run(views(scene, sensors));
        std::vector<std::string> stages;
        for (const KernelTime& t : plan.profile()) stages.push_back(t.name);
        ASSERT_GE(stages.size(), 3u) << to_string(policy);
        const bool on_device = policy == SkipPolicy::Idle;
        EXPECT_EQ(stages[0] == "change_detect" && stages[1] == "compact", on_device) << to_string(policy);
        EXPECT_EQ(std::count(stages.begin(), stages.end(), "change_detect"), on_device ? 1 : 0) << to_string(policy);
        EXPECT_EQ(plan.submits(), 1u) << to_string(policy);
    }
}

}  // namespace
}  // namespace vkfuse::test

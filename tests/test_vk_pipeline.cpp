// Two cycles in flight (PlanConfig::cycles_in_flight, Plan::submit/collect):
// each collected cycle holds exactly what a round trip of the same frames
// gives, while the next cycle runs; misuse is refused with one message.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/vk/interop.hpp"

namespace vkfuse::test {
namespace {

constexpr int kH = 48, kW = 64, kK = 3, kS = 3, kCycles = 5;

PlanConfig config(Method method, int in_flight) {
    PlanConfig cfg;
    cfg.fusion.method = method;
    cfg.fusion.levels = 2;  // what 48x64 carries of bior4.4
    cfg.height = kH;
    cfg.width = kW;
    cfg.frames = kK;
    cfg.sensors = kS;
    cfg.metrics = MetricSet::all();
    cfg.cycles_in_flight = in_flight;
    return cfg;
}

// Cycle c's frames: sensor-major, every cycle and sensor different.
std::vector<Image> cycle_frames(int c) {
    std::vector<Image> frames;
    for (int s = 0; s < kS; ++s)
        for (int k = 0; k < kK; ++k)
            frames.push_back(convert<float>(structured_image(kH, kW, 3, std::uint32_t(1000 * c + 10 * s + k))));
    return frames;
}
std::vector<FrameView> views(const std::vector<Image>& frames) {
    std::vector<FrameView> v;
    for (const Image& f : frames) v.push_back(FrameView::of(f));
    return v;
}

bool same_bits(const Image& a, const Image& b) {
    return a.data.size() == b.data.size() && std::memcmp(a.data.data(), b.data.data(), a.data.size() * 4) == 0;
}

void set_backgrounds(Plan& plan, int seed) {
    for (int s = 0; s < kS; ++s)
        plan.set_background(s, FrameView::of(convert<float>(structured_image(kH, kW, 3, std::uint32_t(seed + s)))));
}

class VulkanPipeline : public VulkanTest, public ::testing::WithParamInterface<Method> {};

// The pipelined plan submits cycle c + 1 before it collects cycle c, and c's
// results are read while c + 1 runs: each equals the round trip's to the bit
// (the same kernels on the same frames) and the reference within tolerance.
TEST_P(VulkanPipeline, EachCollectedCycleIsTheRoundTripsWhileTheNextRuns) {
    Plan round_trip(ctx(), config(GetParam(), 1)), pipelined(ctx(), config(GetParam(), 2));
    set_backgrounds(round_trip, 7);
    set_backgrounds(pipelined, 7);
    std::vector<std::vector<Image>> frames;
    for (int c = 0; c < kCycles; ++c) frames.push_back(cycle_frames(c));
    pipelined.submit(views(frames[0]));
    EXPECT_EQ(pipelined.in_flight(), 1);
    for (int c = 0; c < kCycles; ++c) {
        if (c + 1 < kCycles) pipelined.submit(views(frames[std::size_t(c) + 1]));
        EXPECT_EQ(pipelined.in_flight(), c + 1 < kCycles ? 2 : 1);
        pipelined.collect();
        round_trip.run(views(frames[std::size_t(c)]));
        for (int s = 0; s < kS; ++s) {
            SCOPED_TRACE("cycle " + std::to_string(c) + ", sensor " + std::to_string(s));
            EXPECT_TRUE(same_bits(pipelined.fused(s), round_trip.fused(s)));
            const Metrics a = pipelined.metrics(s), b = round_trip.metrics(s);
            EXPECT_EQ(a.sharpness, b.sharpness);
            EXPECT_EQ(a.contrast, b.contrast);
            EXPECT_EQ(a.background_diff, b.background_diff);
            std::vector<ImageD> in;
            for (int k = 0; k < kK; ++k) in.push_back(convert<double>(frames[std::size_t(c)][std::size_t(s * kK + k)]));
            EXPECT_LT(max_abs_diff(pipelined.fused(s), fuse_reference(in, pipelined.config().fusion)), 1e-4);
        }
    }
    EXPECT_EQ(pipelined.in_flight(), 0);
    EXPECT_EQ(pipelined.submits(), std::uint64_t(kCycles));
}

INSTANTIATE_TEST_SUITE_P(Methods, VulkanPipeline, ::testing::Values(Method::Brovey, Method::Laplacian, Method::Wavelet),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// A background set while a cycle is in flight applies from the next
// submitted cycle on: the cycle in flight keeps the one it was submitted with.
TEST_F(VulkanTest, ABackgroundSetInFlightAppliesFromTheNextCycle) {
    Plan round_trip(ctx(), config(Method::Laplacian, 1)), pipelined(ctx(), config(Method::Laplacian, 2));
    set_backgrounds(round_trip, 7);
    set_backgrounds(pipelined, 7);
    const std::vector<Image> first = cycle_frames(0), second = cycle_frames(1);
    pipelined.submit(views(first));
    set_backgrounds(pipelined, 99);  // while cycle 0 is in flight
    pipelined.submit(views(second));
    pipelined.collect();
    round_trip.run(views(first));
    for (int s = 0; s < kS; ++s) EXPECT_EQ(pipelined.metrics(s).background_diff, round_trip.metrics(s).background_diff);
    pipelined.collect();
    set_backgrounds(round_trip, 99);
    round_trip.run(views(second));
    for (int s = 0; s < kS; ++s) EXPECT_EQ(pipelined.metrics(s).background_diff, round_trip.metrics(s).background_diff);
}

void expect_refusal(const std::function<void()>& call, const std::string& words) {
    try {
        call();
        ADD_FAILURE() << "no error; expected one saying: " << words;
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
}

TEST_F(VulkanTest, PipelineMisuseIsRefusedWithOneMessage) {
    const std::vector<Image> frames = cycle_frames(0);
    Plan plan(ctx(), config(Method::Brovey, 2));
    set_backgrounds(plan, 7);
    expect_refusal([&] { plan.collect(); }, "no cycle in flight");
    expect_refusal([&] { plan.fused(0); }, "before run()");
    plan.submit(views(frames));
    expect_refusal([&] { plan.metrics(0); }, "after submit(); collect() its cycle first");
    plan.submit(views(frames));
    expect_refusal([&] { plan.submit(views(frames)); }, "2 cycle(s) in flight already");
    plan.collect();
    EXPECT_NO_THROW(plan.fused(0));
    plan.run(views(frames));  // collects the cycle still in flight first
    EXPECT_EQ(plan.in_flight(), 0);
    EXPECT_NO_THROW(plan.metrics(0));

    Plan one(ctx(), config(Method::Brovey, 1));
    set_backgrounds(one, 7);
    one.submit(views(frames));
    expect_refusal([&] { one.submit(views(frames)); }, "1 cycle(s) in flight already");

    PlanConfig three = config(Method::Brovey, 3);
    expect_refusal([&] { Plan p(ctx(), three); }, "cycles_in_flight must be 1 or 2, got 3");
    PlanConfig skipping = config(Method::Wavelet, 2);
    skipping.input = PixelType::U8;
    skipping.skip.policy = SkipPolicy::Idle;
    expect_refusal([&] { Plan p(ctx(), skipping); }, "a skipping plan keeps its references and held results once");
    expect_refusal([&] { make_plan(ctx(), config(Method::Brovey, 2), PlanBuffers{}); }, "keeps 1 cycle in flight");
}

// A plan of one lane takes submit() and collect() too: one round trip split.
TEST_F(VulkanTest, OneCycleInFlightSplitsTheRoundTrip) {
    const std::vector<Image> frames = cycle_frames(3);
    Plan a(ctx(), config(Method::Wavelet, 1)), b(ctx(), config(Method::Wavelet, 1));
    set_backgrounds(a, 7);
    set_backgrounds(b, 7);
    a.submit(views(frames));
    a.collect();
    b.run(views(frames));
    for (int s = 0; s < kS; ++s) EXPECT_TRUE(same_bits(a.fused(s), b.fused(s)));
}

}  // namespace
}  // namespace vkfuse::test

// Misuse of the library's GPU API, case by case: every call throws a
// vkfuse::Error of the right kind whose one line names the object and the
// problem; none aborts, and the plan stays usable after a rejected call.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "vk_fixture.hpp"

namespace vkfuse::test {
namespace {

struct Misuse {
    std::string name;
    std::function<void(Context&)> call;
    std::string subject;  // what the message starts with, before ": "
    ErrorKind kind;
    std::string fragment;
};

PlanConfig config(Method method, int h, int w, int c, int frames, int sensors = 1) {
    PlanConfig cfg;
    cfg.fusion.method = method;
    cfg.height = h;
    cfg.width = w;
    cfg.channels = c;
    cfg.frames = frames;
    cfg.sensors = sensors;
    return cfg;
}

std::function<void(Context&)> make(PlanConfig cfg) {
    return [cfg](Context& ctx) { Plan plan(ctx, cfg); };
}

PlanConfig with(PlanConfig cfg, const std::function<void(PlanConfig&)>& change) {
    change(cfg);
    return cfg;
}

std::vector<Misuse> bad_configs() {
    const PlanConfig ok = with(config(Method::Wavelet, 16, 16, 3, 2), [](auto& c) { c.fusion.wavelet = Wavelet::Haar; });
    return {
        {"zero_height", make(with(ok, [](auto& c) { c.height = 0; })), "image size 0x16", ErrorKind::InvalidArgument,
         "both sides must be >= 1"},
        {"two_channels", make(with(ok, [](auto& c) { c.channels = 2; })), "image channels 2",
         ErrorKind::InvalidArgument, "must be 1 (gray) or 3 (RGB)"},
        {"no_frames", make(with(ok, [](auto& c) { c.frames = 0; })), "frames", ErrorKind::InvalidArgument,
         "need at least 1, got 0"},
        {"no_sensors", make(with(ok, [](auto& c) { c.sensors = 0; })), "plan", ErrorKind::InvalidArgument,
         "sensors must be >= 1"},
        {"negative_levels", make(with(ok, [](auto& c) { c.fusion.levels = -2; })), "--levels -2",
         ErrorKind::InvalidArgument, "must be >= 0"},
        {"wavelet_levels", make(with(ok, [](auto& c) { c.fusion.levels = 9; })), "--levels 9",
         ErrorKind::InvalidArgument, "a 16x16 image carries at most 4 levels of haar"},
        {"laplacian_levels", make(with(config(Method::Laplacian, 16, 16, 1, 2), [](auto& c) { c.fusion.levels = 33; })),
         "--levels 33", ErrorKind::InvalidArgument, "at most 32 levels"},
        {"channel_sum_gray", make(config(Method::ChannelSum, 8, 8, 1, 3)), "--method channel-sum",
         ErrorKind::InvalidArgument, "needs 3-channel (RGB) frames"},
        {"unfused_two_frames", make(with(config(Method::Brovey, 8, 8, 1, 2), [](auto& c) { c.fuse = false; })),
         "plan", ErrorKind::InvalidArgument, "an unfused plan (fuse = false) scores 1 frame per sensor, got 2"},
        {"beyond_32_bit_indexing", make(config(Method::Brovey, 8192, 8192, 3, 16, 64)), "plan",
         ErrorKind::InvalidArgument, "64 sensors x 16 frames of 8192x8192 exceed one plan's size limit"},
    };
}

class VulkanApiErrors : public VulkanTest {};

TEST_F(VulkanApiErrors, BadConfigurationsAreRejectedBeforeAnyWork) {
    for (const Misuse& m : bad_configs()) {
        SCOPED_TRACE(m.name);
        expect_error([&] { m.call(ctx()); }, m.subject, m.kind, m.fragment);
    }
}

TEST_F(VulkanApiErrors, BadRunsAndReadsLeaveThePlanUsable) {
    PlanConfig cfg = config(Method::Brovey, 8, 8, 3, 2, 2);
    cfg.metrics = MetricSet::all();
    Plan plan(ctx(), cfg);
    const Image frame(8, 8, 3), narrow(8, 7, 3);
    const std::vector<std::uint8_t> bytes(8 * 8 * 3);
    auto views = [&](FrameView odd, std::size_t at) {
        std::vector<FrameView> v(4, FrameView::of(frame));
        v[at] = odd;
        return v;
    };
    expect_error([&] { plan.fused(0); }, "plan", ErrorKind::InvalidArgument, "fused() before run()");
    expect_error([&] { plan.metrics(0); }, "plan", ErrorKind::InvalidArgument, "metrics() before run()");
    expect_error([&] { plan.run(std::vector<FrameView>(3, FrameView::of(frame))); }, "plan run",
                 ErrorKind::InvalidArgument, "got 3 frames, expected 2 sensors x 2 = 4");
    expect_error([&] { plan.run(views(FrameView{nullptr, 8, 8, 3, PixelType::F32}, 1)); }, "frame 1 of sensor 0",
                 ErrorKind::InvalidArgument, "no pixel data");
    expect_error([&] { plan.run(views(FrameView::of(narrow), 2)); }, "frame 0 of sensor 1", ErrorKind::Shape,
                 "shape 8x7x3 differs from the plan's 8x8x3");
    expect_error([&] { plan.run(views(FrameView{bytes.data(), 8, 8, 3, PixelType::U8}, 3)); }, "frame 1 of sensor 1",
                 ErrorKind::InvalidArgument, "pixel type differs from the plan's");
    expect_error([&] { plan.run(views(FrameView::of(frame), 0)); }, "plan run", ErrorKind::InvalidArgument,
                 "no background set for sensor 0");
    expect_error([&] { plan.set_background(2, FrameView::of(frame)); }, "background", ErrorKind::InvalidArgument,
                 "sensor 2 out of range");
    expect_error([&] { plan.set_background(0, FrameView::of(narrow)); }, "background of sensor 0", ErrorKind::Shape,
                 "differs from the plan's");
    // After all that, a correct cycle still runs.
    plan.set_background(0, FrameView::of(frame));
    plan.set_background(1, FrameView::of(frame));
    plan.run(views(FrameView::of(frame), 0));
    EXPECT_EQ(plan.fused(1).size(), frame.size());
    expect_error([&] { plan.fused(2); }, "plan", ErrorKind::InvalidArgument, "sensor 2 out of range");
    expect_error([&] { plan.metrics(-1); }, "plan", ErrorKind::InvalidArgument, "sensor -1 out of range");
    expect_error([&] { plan.profile(); }, "plan", ErrorKind::InvalidArgument, "created without profile");
}

TEST_F(VulkanApiErrors, ResultsThatWereNotAskedForAreErrors) {
    PlanConfig cfg = config(Method::Brovey, 4, 4, 1, 1);
    cfg.fuse = false;
    cfg.want_fused = false;
    cfg.metrics = {};
    Plan plan(ctx(), cfg);
    const Image frame(4, 4, 1);
    const FrameView view = FrameView::of(frame);
    plan.run(std::span(&view, 1));
    expect_error([&] { plan.fused(0); }, "plan", ErrorKind::InvalidArgument, "created without want_fused");
    expect_error([&] { plan.metrics(0); }, "plan", ErrorKind::InvalidArgument, "created without metrics");
    expect_error([&] { plan.set_background(0, view); }, "plan", ErrorKind::InvalidArgument,
                 "created without the background_diff metric");
}

}  // namespace
}  // namespace vkfuse::test

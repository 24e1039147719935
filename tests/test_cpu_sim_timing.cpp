// The simulated DIGIT in time: LED latency, rolling shutter, clocks, truth.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "expect_error.hpp"
#include "sim_support.hpp"

namespace vkfuse {
namespace {

const Illumination kWhite({15, 15, 15}), kOff({0, 0, 0});

// A switch requested after a few frames, at sensor time `requested`; frames
// around it, with their truths.
struct Switch {
    double requested = 0;
    double effective = 0;
    std::vector<Frame> frames;
    std::vector<SimFrameTruth> truths;
};

Switch switch_off(SimDigit& sim, double latency) {
    for (int i = 0; i < 3; ++i) sim.grab();
    Switch s;
    s.requested = double(sim.truth(2).timestamp) + sim.timing().frame_span_s(sim.truth(2).exposure_s);
    s.effective = s.requested + latency;
    sim.set_illumination(kOff);
    for (int i = 0; i < 12; ++i) {
        s.frames.push_back(sim.grab());
        s.truths.push_back(sim.truth(s.frames.back().index));
    }
    return s;
}

TEST(SimTiming, FramesBeforeTheLatencyAreOldThenMixedThenNew) {
    SimDigitOptions o;
    o.object = "nothing";
    o.camera_auto = false;
    o.led_latency_s = 0.05;
    SimDigit sim(o);
    const Switch s = switch_off(sim, o.led_latency_s);
    const SimTiming timing = sim.timing();
    int mixed = 0;
    for (const SimFrameTruth& t : s.truths) {
        const double end = t.timestamp + timing.frame_span_s(t.exposure_s);
        if (end <= s.effective) {
            EXPECT_FALSE(t.mixed) << "frame " << t.index;
            EXPECT_EQ(t.lit_by, kWhite) << "frame " << t.index;
        } else if (t.timestamp >= s.effective) {
            EXPECT_FALSE(t.mixed) << "frame " << t.index;
            EXPECT_EQ(t.lit_by, kOff) << "frame " << t.index;
        } else {
            EXPECT_TRUE(t.mixed) << "frame " << t.index;
            EXPECT_TRUE(t.lit_by.levels().empty());
            EXPECT_EQ(t.settings, (std::vector<Illumination>{kWhite, kOff}));
            ++mixed;
        }
    }
    // The exposure of a frame (1.4 periods, rows read over 0.9 of one)
    // overlaps the next: a switch always lands in one or two frames.
    EXPECT_GE(mixed, 1);
    EXPECT_LE(mixed, 2);
    EXPECT_EQ(s.truths.front().lit_by, kWhite);
    EXPECT_EQ(s.truths.back().lit_by, kOff);
}

TEST(SimTiming, RowsOfAMixedFrameMixByTheirExposureUnderEachSetting) {
    SimDigitOptions o;
    o.object = "nothing";
    o.camera_auto = false;
    SimDigit reference(o);
    const ImageD lit = test::to_image(reference.grab());
    SimDigit sim(o);
    const Switch s = switch_off(sim, o.led_latency_s);
    const SimTiming timing = sim.timing();
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
        if (!s.truths[i].mixed) continue;
        const ImageD img = test::to_image(s.frames[i]);
        double worst = 0;
        for (int r = 0; r < img.height; ++r) {
            // Fraction of row r's exposure still under the white setting.
            const double begin = s.truths[i].timestamp + r * timing.row_time_s;
            const double on = std::clamp((s.effective - begin) / s.truths[i].exposure_s, 0.0, 1.0);
            double got = 0, full = 0;
            for (int x = 0; x < img.width; ++x)
                for (int c = 0; c < 3; ++c) {
                    got += img.at(r, x, c);
                    full += lit.at(r, x, c);
                }
            worst = std::max(worst, std::abs(got / full - on));
        }
        EXPECT_LT(worst, 0.03) << "frame " << s.truths[i].index;
    }
}

TEST(SimTiming, ARealClockMakesGrabWaitForTheFrame) {
    SimDigitOptions o;
    o.object = "nothing";
    o.clock = make_real_clock();
    SimDigit sim(o);
    // The sensor's clock started before the simulator rendered its scene, which
    // can take a while on a loaded host: what grab has to wait is counted from
    // here, not from the clock's zero.
    const double t0 = o.clock->now();
    const auto start = std::chrono::steady_clock::now();
    Frame f;
    for (int i = 0; i < 4; ++i) f = sim.grab();
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double expected = f.timestamp + sim.timing().frame_span_s(sim.truth(f.index).exposure_s);
    EXPECT_GE(o.clock->now(), expected);
    EXPECT_GT(waited, 0.5 * (expected - t0));  // it really slept: 3 periods and a frame span
}

TEST(SimTiming, ALateCallerGetsTheNewestFrame) {
    SimDigitOptions o;
    o.object = "nothing";
    o.clock = make_virtual_clock();
    SimDigit sim(o);
    EXPECT_EQ(sim.grab().index, 0u);
    o.clock->wait_until(1.0);  // a second passes elsewhere: the camera streamed on
    const Frame f = sim.grab();
    EXPECT_EQ(f.index, 58u);   // the newest frame complete at t = 1 s
    EXPECT_EQ(sim.grab().index, 59u);
    test::expect_error([&] { sim.truth(30); }, "SIM-0001", ErrorKind::InvalidArgument, "no ground truth kept for frame 30");
}

TEST(SimTiming, RequestsAreRelativeToTheSensorsClock) {
    SimDigitOptions o;
    o.object = "nothing";
    o.camera_auto = false;
    o.clock = make_virtual_clock();
    o.clock->wait_until(10.0);  // the sensor starts at t = 10 s
    SimDigit sim(o);
    EXPECT_DOUBLE_EQ(sim.grab().timestamp, 10.0);
    sim.set_illumination(kOff);  // at 10 s + one frame span; effective 25 ms later
    Frame f;
    do f = sim.grab();
    while (sim.truth(f.index).lit_by != kOff);
    EXPECT_GE(f.timestamp, 10.0 + sim.timing().frame_span_s(sim.timing().nominal_exposure_s) + o.led_latency_s);
    EXPECT_LT(f.timestamp, 10.0 + 0.1);
}

TEST(SimTiming, BadRequestsAndOptionsAreErrorsNamingTheSerial) {
    using test::expect_error;
    const auto k = ErrorKind::InvalidArgument;
    SimDigit sim;
    expect_error([&] { sim.set_illumination(Illumination({16, 0, 0})); }, "SIM-0001", k,
                 "illumination 16,0,0: level 16 of r exceeds 15");
    expect_error([&] { sim.set_illumination(Illumination({1, 2})); }, "SIM-0001", k, "2 levels");
    expect_error([&] { sim.set_illumination(Illumination({0, -1, 0})); }, "SIM-0001", k, "below 0");
    expect_error([&] { sim.set_object("spoon"); }, "SIM-0001", k, "unknown object \"spoon\"");
    expect_error([&] { sim.set_object("ball", 3.0); }, "SIM-0001", k, "press depth");
    expect_error([&] { sim.set_object("ball", -0.1); }, "SIM-0001", k, "press depth");
    expect_error([&] { sim.move_object(1.5, 0.5); }, "SIM-0001", k, "position");
    SimDigitOptions o;
    o.serial = "SIM-XY";
    o.object = "teapot";
    expect_error([&] { SimDigit bad(o); }, "SIM-XY", k, "unknown object \"teapot\"");
    o.object = "ball";
    o.led_latency_s = -1;
    expect_error([&] { SimDigit bad(o); }, "SIM-XY", k, "LED latency");
    o.led_latency_s = 0.01;
    o.y = std::nan("");
    expect_error([&] { SimDigit bad(o); }, "SIM-XY", k, "position");
}

}  // namespace
}  // namespace vkfuse

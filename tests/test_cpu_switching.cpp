// Switch-latency calibration and the frame scheduler against the simulated
// DIGIT's ground truth: every frame handed out must be lit by one setting.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "expect_error.hpp"
#include "sensor_doubles.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse::test {
namespace {

struct Bench {
    std::shared_ptr<Clock> clock = make_virtual_clock();
    std::shared_ptr<SimDigit> sim;
    std::shared_ptr<TruthLoggingSensor> sensor;

    explicit Bench(double latency_s, bool vga = false, bool camera_auto = false) {
        SimDigitOptions o;
        o.led_latency_s = latency_s;
        o.vga = vga;
        o.camera_auto = camera_auto;
        o.clock = clock;
        sim = std::make_shared<SimDigit>(o);
        sensor = std::make_shared<TruthLoggingSensor>(sim);
    }
    void expect_lit_by(const Frame& f, const Illumination& setting) const {
        const SimFrameTruth t = sensor->truth(f.index);
        EXPECT_FALSE(t.mixed) << "frame " << f.index;
        EXPECT_EQ(t.lit_by, setting) << "frame " << f.index;
    }
};

// The measured bounds hold the simulator's true latency and rolling-shutter
// span, and are tight enough to schedule by (a fraction of a frame), with the
// camera's exposure fixed.
TEST(SwitchTiming, BoundsHoldTheTruth) {
    for (double latency : {0.0, 1.5 / 60, 0.08, 0.2}) {
        SCOPED_TRACE("latency " + std::to_string(latency));
        Bench b(latency);
        const SwitchTiming t = measure_switch_timing(*b.sensor, *b.clock);
        const SimTiming truth = b.sim->timing();
        const double clearance = truth.frame_span_s(truth.nominal_exposure_s) - latency;
        EXPECT_NEAR(t.frame_period, truth.frame_period_s, 1e-9);
        EXPECT_GE(t.latency_max, latency);
        EXPECT_LE(t.latency_max, latency + 0.25 * truth.frame_period_s);
        EXPECT_GE(t.clearance, clearance);
        EXPECT_LE(t.clearance, clearance + 0.25 * truth.frame_period_s);
    }
}

// With the camera's auto exposure on (as a DIGIT streams), frames are right
// only once it has settled after a switch, and an unlit gel is exposed
// longest: the bounds cover both.
TEST(SwitchTiming, AutoExposureWidensTheBounds) {
    const double latency = 1.5 / 60;
    Bench b(latency, false, true);
    const SwitchTiming t = measure_switch_timing(*b.sensor, *b.clock);
    const SimTiming truth = b.sim->timing();
    EXPECT_GE(t.latency_max, latency + truth.frame_period_s);  // at least a frame of settling
    EXPECT_GE(t.clearance, truth.frame_span_s(truth.max_exposure_s) - latency);
}

TEST(Switcher, EveryCycleFrameIsLitByItsSettingAlone) {
    const IlluminationSequence seq = parse_sequence("15,15,15+0,15,0+15,0,0+0,0,15");
    struct Case {
        double latency;
        bool vga, camera_auto;
    };
    for (const Case& c :
         {Case{1.5 / 60, false, false}, {0.01, false, false}, {0.08, true, false}, {1.5 / 60, false, true}}) {
        SCOPED_TRACE("latency " + std::to_string(c.latency) + (c.vga ? " VGA" : " QVGA") +
                     (c.camera_auto ? " auto" : ""));
        Bench b(c.latency, c.vga, c.camera_auto);
        Switcher sw(*b.sensor, b.clock, measure_switch_timing(*b.sensor, *b.clock));
        for (int c = 0; c < 12; ++c) {
            const std::vector<Frame> frames = sw.next_cycle(seq);
            ASSERT_EQ(frames.size(), seq.size());
            for (std::size_t k = 0; k < seq.size(); ++k) b.expect_lit_by(frames[k], seq[k]);
        }
    }
}

// With the rolling shutter spanning more than one frame period, a setting
// costs two frames at best; the scheduler reaches that, LED latency or not,
// because it requests the next setting before the frame in hand is read out.
TEST(Switcher, LosesNoFrameBeyondWhatTheShutterForces) {
    const IlluminationSequence seq = parse_sequence("15,15,15+0,15,0+0,0,15");
    for (double latency : {1.5 / 60, 0.08}) {
        Bench b(latency);
        Switcher sw(*b.sensor, b.clock, measure_switch_timing(*b.sensor, *b.clock));
        const SimTiming truth = b.sim->timing();
        const int frames_per_setting =
            int(std::ceil(truth.frame_span_s(truth.nominal_exposure_s) / truth.frame_period_s));
        std::uint64_t first = sw.next_cycle(seq).back().index;
        for (int c = 0; c < 20; ++c) {
            const std::uint64_t last = sw.next_cycle(seq).back().index;
            EXPECT_EQ(last - first, std::uint64_t(frames_per_setting) * seq.size()) << "cycle " << c;
            first = last;
        }
    }
}

TEST(Switcher, CaptureGivesConsecutiveCleanFrames) {
    Bench b(0.08);
    Switcher sw(*b.sensor, b.clock, measure_switch_timing(*b.sensor, *b.clock));
    for (const char* text : {"0,15,0", "5,5,5", "0,15,0"}) {
        const Illumination setting = Illumination::parse(text);
        const std::vector<Frame> frames = sw.capture(setting, 5);
        ASSERT_EQ(frames.size(), 5u);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            b.expect_lit_by(frames[i], setting);
            if (i > 0) {
                EXPECT_EQ(frames[i].index, frames[i - 1].index + 1);
            }
        }
    }
}

// A sensor whose LEDs do nothing cannot be calibrated; the message says so
// and names the sensor.
class DeafSensor : public Sensor {
public:
    explicit DeafSensor(std::shared_ptr<SimDigit> sim) : sim_(std::move(sim)) {}
    SensorInfo info() const override { return sim_->info(); }
    void set_illumination(const Illumination&) override {}
    Frame grab() override { return sim_->grab(); }

private:
    std::shared_ptr<SimDigit> sim_;
};

TEST(SwitchTiming, LedsThatDoNothingAreReported) {
    Bench b(0.0);
    DeafSensor deaf(b.sim);
    expect_error([&] { measure_switch_timing(deaf, *b.clock); }, "SIM-0001", ErrorKind::Device, "barely change");
}

TEST(Switcher, ByLabelNeedsLabelledFrames) {
    Bench b(0.0);
    Switcher sw = Switcher::labelled(*b.sensor);
    expect_error([&] { sw.capture(Illumination::parse("15,15,15"), 1); }, "SIM-0001", ErrorKind::InvalidArgument,
                 "carries no illumination");
}

TEST(Switcher, UnmeasuredTimingIsRefused) {
    Bench b(0.0);
    expect_error([&] { Switcher(*b.sensor, b.clock, SwitchTiming{}); }, "SIM-0001", ErrorKind::InvalidArgument,
                 "not measured");
}

}  // namespace
}  // namespace vkfuse::test

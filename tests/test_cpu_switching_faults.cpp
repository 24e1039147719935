// The scheduler under late and dropped frames, and the calibrated clearance
// against the simulator's truth over several latency / exposure
// configurations. test_cpu_switching.cpp covers the well-behaved sensor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "sensor_doubles.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse::test {
namespace {

// A simulated DIGIT (its truth logged) that, once armed, loses some of the
// frames a scheduler waits for: the first frame lit by one setting alone and
// stamped at least latency_max after a request, for each request. It loses the n-th of those frames for each n in `which`
// (irregularly spaced, so no slot is lost again and again until the sensor
// is rightly given up on):
//  - Drop: the frame is lost on the way (its index never appears) and the
//    next one is handed out instead;
//  - Late: the host thread comes back `late_periods` frame periods late, so
//    the sensor has streamed on and the frame handed out is the newest one,
//    stamped past the window the scheduler expected the lost frame in.
class UnreliableSensor : public Sensor {
public:
    enum class Fault { Drop, Late };
    UnreliableSensor(std::shared_ptr<TruthLoggingSensor> inner, std::shared_ptr<Clock> clock, double period,
                     Fault fault, std::set<int> which, double late_periods = 1.5)
        : inner_(std::move(inner)),
          clock_(std::move(clock)),
          period_(period),
          fault_(fault),
          which_(std::move(which)),
          late_periods_(late_periods) {}

    void arm(const SwitchTiming& timing) {
        armed_ = true;
        latency_max_ = timing.latency_max;
    }
    int faults() const { return int(lost_.size()); }
    const std::set<std::uint64_t>& lost() const { return lost_; }

    SensorInfo info() const override { return inner_->info(); }
    void set_illumination(const Illumination& s) override {
        if (armed_) requests_.push_back(clock_->now());
        inner_->set_illumination(s);
    }
    Frame grab() override {
        Frame f = inner_->grab();
        if (!armed_ || inner_->truth(f.index).mixed || requests_.empty() ||
            f.timestamp < requests_.front() + latency_max_)
            return f;
        // The first clean frame after the oldest request not yet served.
        while (!requests_.empty() && f.timestamp >= requests_.front() + latency_max_) requests_.pop_front();
        if (!which_.count(++awaited_)) return f;
        lost_.insert(f.index);
        if (fault_ == Fault::Late) clock_->wait_until(clock_->now() + late_periods_ * period_);
        return inner_->grab();
    }

private:
    std::shared_ptr<TruthLoggingSensor> inner_;
    std::shared_ptr<Clock> clock_;
    double period_;
    Fault fault_;
    std::set<int> which_;
    double late_periods_;
    bool armed_ = false;
    double latency_max_ = 0;
    std::deque<double> requests_;
    int awaited_ = 0;
    std::set<std::uint64_t> lost_;
};

struct SensorSetup {
    double latency;
    bool vga, camera_auto;
    std::string describe() const {
        return "latency " + std::to_string(latency) + (vga ? " VGA" : " QVGA") + (camera_auto ? " auto" : " fixed");
    }
};

struct Rigged {
    std::shared_ptr<Clock> clock = make_virtual_clock();
    std::shared_ptr<SimDigit> sim;
    std::shared_ptr<TruthLoggingSensor> truth;
    explicit Rigged(const SensorSetup& s) {
        SimDigitOptions o;
        o.led_latency_s = s.latency;
        o.vga = s.vga;
        o.camera_auto = s.camera_auto;
        o.clock = clock;
        sim = std::make_shared<SimDigit>(o);
        truth = std::make_shared<TruthLoggingSensor>(sim);
    }
};

struct RunResult {
    std::uint64_t requests = 0;
    int faults = 0;
};

// Calibrates, then takes `cycles` cycles through a sensor that loses the
// awaited frames listed in `which` (none: a clean run) and checks every frame it hands out against the truth.
RunResult run_cycles(const SensorSetup& setup, UnreliableSensor::Fault fault, const std::set<int>& which, int cycles,
                     const IlluminationSequence& seq) {
    Rigged r(setup);
    UnreliableSensor sensor(r.truth, r.clock, r.sim->timing().frame_period_s, fault, which);
    const SwitchTiming timing = measure_switch_timing(sensor, *r.clock);
    sensor.arm(timing);
    Switcher sw(sensor, r.clock, timing);
    std::set<std::uint64_t> used;
    for (int c = 0; c < cycles; ++c) {
        const std::vector<Frame> frames = sw.next_cycle(seq);
        EXPECT_EQ(frames.size(), seq.size());
        if (frames.size() != seq.size()) break;
        for (std::size_t k = 0; k < seq.size(); ++k) {
            const SimFrameTruth t = r.truth->truth(frames[k].index);
            EXPECT_FALSE(t.mixed) << "cycle " << c << " slot " << k << " frame " << frames[k].index;
            EXPECT_EQ(t.lit_by.to_string(), seq[k].to_string()) << "cycle " << c << " slot " << k << " frame " << frames[k].index;
            EXPECT_TRUE(used.insert(frames[k].index).second) << "frame " << frames[k].index << " placed twice";
            EXPECT_FALSE(sensor.lost().count(frames[k].index)) << "a lost frame was placed";
        }
    }
    return {sw.requests_made(), sensor.faults()};
}

// The same through sliding windows: every frame of every window clean, lit by
// its slot's setting, never a lost one, and the windows' span within the
// bound; windows that a lost frame would stretch past it are held.
RunResult run_windows(const SensorSetup& setup, UnreliableSensor::Fault fault, const std::set<int>& which, int windows,
                      const IlluminationSequence& seq, std::uint64_t& held) {
    Rigged r(setup);
    UnreliableSensor sensor(r.truth, r.clock, r.sim->timing().frame_period_s, fault, which);
    const SwitchTiming timing = measure_switch_timing(sensor, *r.clock);
    sensor.arm(timing);
    Switcher sw(sensor, r.clock, timing);
    const double bound = window_bound(timing, seq.size());
    std::uint64_t newest = 0;
    for (int w = 0; w < windows; ++w) {
        const std::vector<Frame> frames = sw.next_window(seq);
        EXPECT_EQ(frames.size(), seq.size());
        if (frames.size() != seq.size()) break;
        double lo = frames[0].timestamp, hi = lo;
        std::uint64_t latest = 0;
        for (std::size_t k = 0; k < seq.size(); ++k) {
            const SimFrameTruth t = r.truth->truth(frames[k].index);
            EXPECT_FALSE(t.mixed) << "window " << w << " slot " << k << " frame " << frames[k].index;
            EXPECT_EQ(t.lit_by.to_string(), seq[k].to_string()) << "window " << w << " slot " << k;
            EXPECT_FALSE(sensor.lost().count(frames[k].index)) << "a lost frame was placed";
            lo = std::min(lo, frames[k].timestamp);
            hi = std::max(hi, frames[k].timestamp);
            latest = std::max(latest, frames[k].index);
        }
        EXPECT_LE(hi - lo, bound + 1e-9) << "window " << w;
        EXPECT_GT(latest, newest) << "window " << w << " brought no new frame";
        newest = latest;
    }
    held = sw.windows_held();
    return {sw.requests_made(), sensor.faults()};
}

// Which awaited frames are lost: irregular, a few per cycle of four settings.
const std::set<int> kLost{2, 7, 13, 20, 26, 33};

const IlluminationSequence& sequence() {
    static const IlluminationSequence seq = parse_sequence("15,15,15+0,15,0+15,0,0+0,0,15");
    return seq;
}

// A frame lost on the way: the slot whose frame it was sees its window close
// empty (or the next frame stamped past it) and asks again; every frame that
// is placed was lit by its slot's setting alone.
TEST(SwitcherFaults, DroppedFramesAreRequestedAgainAndNeverMixed) {
    for (const SensorSetup& s : {SensorSetup{1.5 / 60, false, false}, SensorSetup{0.08, false, false}, SensorSetup{0.01, false, true}}) {
        SCOPED_TRACE(s.describe());
        const RunResult clean = run_cycles(s, UnreliableSensor::Fault::Drop, {}, 10, sequence());
        const RunResult faulty = run_cycles(s, UnreliableSensor::Fault::Drop, kLost, 10, sequence());
        EXPECT_EQ(faulty.faults, int(kLost.size()));
        EXPECT_GT(faulty.requests, clean.requests) << "no slot was requested again";
    }
}

// The thread comes back late, past the clearance: the frame it gets is stamped
// after the next switch may already have landed; it must not be placed in the
// slot it was waited for, and that slot is requested again.
TEST(SwitcherFaults, LateFramesAreRejectedAndRequestedAgain) {
    for (const SensorSetup& s : {SensorSetup{1.5 / 60, false, false}, SensorSetup{0.08, false, false}, SensorSetup{0.01, false, true}}) {
        SCOPED_TRACE(s.describe());
        const RunResult clean = run_cycles(s, UnreliableSensor::Fault::Late, {}, 10, sequence());
        const RunResult faulty = run_cycles(s, UnreliableSensor::Fault::Late, kLost, 10, sequence());
        EXPECT_EQ(faulty.faults, int(kLost.size()));
        EXPECT_GT(faulty.requests, clean.requests) << "no slot was requested again";
    }
}

// Sliding windows wait for a lost frame's retry instead of fusing without it,
// and hold the windows it would stretch past the bound.
TEST(SwitcherFaults, SlidingWindowsWaitForLostFramesAndStayWithinTheBound) {
    for (const auto fault : {UnreliableSensor::Fault::Drop, UnreliableSensor::Fault::Late}) {
        SCOPED_TRACE(fault == UnreliableSensor::Fault::Drop ? "drop" : "late");
        const SensorSetup s{1.5 / 60, false, false};
        std::uint64_t held_clean = 0, held = 0;
        run_windows(s, fault, {}, 40, sequence(), held_clean);
        const RunResult faulty = run_windows(s, fault, kLost, 40, sequence(), held);
        EXPECT_EQ(faulty.faults, int(kLost.size()));
        EXPECT_EQ(held_clean, 0u);
        EXPECT_GT(held, 0u) << "no window waited for a lost frame's retry";
    }
}

// The calibrated clearance is never below the true one: a request at t must
// leave every frame stamped <= t - clearance untouched, so the bound must
// cover the rolling readout plus the longest exposure minus the LED latency.
// Fixed exposure: the nominal one; auto exposure: up to the longest (an
// unlit gel). The latency bound likewise never undercuts the LED latency.
TEST(SwitchTimingBounds, ClearanceNeverBelowTheTruth) {
    const SensorSetup setups[] = {
        {0.0, false, false},  {0.004, false, false}, {1.5 / 60, false, false}, {0.05, false, false},
        {0.13, false, false}, {0.0, false, true},    {0.06, false, true},      {0.02, true, false},
    };
    for (const SensorSetup& s : setups) {
        SCOPED_TRACE(s.describe());
        Rigged r(s);
        const SwitchTiming t = measure_switch_timing(*r.truth, *r.clock);
        const SimTiming truth = r.sim->timing();
        const double exposure = s.camera_auto ? truth.max_exposure_s : truth.nominal_exposure_s;
        const double true_clearance = truth.frame_span_s(exposure) - s.latency;
        EXPECT_GE(t.clearance, true_clearance) << "measured " << t.clearance << ", true " << true_clearance;
        EXPECT_GE(t.latency_max, s.latency);
        // Still useful for scheduling: within a frame period of the truth.
        EXPECT_LE(t.clearance, true_clearance + truth.frame_period_s);
    }
}

}  // namespace
}  // namespace vkfuse::test

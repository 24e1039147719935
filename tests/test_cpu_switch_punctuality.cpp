// What keeps LED switches on time on a busy host: calibration phases laid on
// the frame grid whatever the thread's lateness, and switch requests (only
// they) under real-time scheduling where the OS allows it. Checked against
// the simulated DIGIT on a virtual clock (a late thread is one that lets the
// clock run on) and against the OS's own answer for SCHED_FIFO.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <memory>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "expect_error.hpp"
#include "sensor/realtime_section.hpp"
#include "vkfuse/sensor/sim_digit.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse::test {
namespace {

// A simulated DIGIT whose reader is late: after each frame the clock runs on
// by a pseudo-random share of a frame period before the caller has it.
// Also notes the calling thread's scheduling policy at each call.
class LateReader : public Sensor {
public:
    LateReader(std::shared_ptr<SimDigit> sim, std::shared_ptr<Clock> clock, double max_delay_s)
        : sim_(std::move(sim)), clock_(std::move(clock)), delay_(0.0, max_delay_s) {}
    SensorInfo info() const override { return sim_->info(); }
    void set_illumination(const Illumination& s) override {
        note(request_policies);
        sim_->set_illumination(s);
    }
    Frame grab() override {
        note(grab_policies);
        Frame f = sim_->grab();
        if (delay_.b() > 0) clock_->wait_until(clock_->now() + delay_(random_));
        return f;
    }
    std::vector<int> request_policies, grab_policies;

private:
    static void note(std::vector<int>& into) { into.push_back(sched_getscheduler(0)); }
    std::shared_ptr<SimDigit> sim_;
    std::shared_ptr<Clock> clock_;
    std::mt19937 random_{20261128};
    std::uniform_real_distribution<double> delay_;
};

struct LateBench {
    std::shared_ptr<Clock> clock = make_virtual_clock();
    std::shared_ptr<SimDigit> sim;
    std::unique_ptr<LateReader> sensor;
    explicit LateBench(double max_delay_frames) {
        SimDigitOptions o;
        o.clock = clock;
        o.camera_auto = false;  // locked, as a rig runs it
        sim = std::make_shared<SimDigit>(o);
        sensor = std::make_unique<LateReader>(sim, clock, max_delay_frames * sim->timing().frame_period_s);
    }
};

// Whether a thread of this process may take SCHED_FIFO at priority, asked of
// the OS directly on a thread of its own.
bool fifo_allowed(int priority) {
    bool allowed = false;
    std::thread([&] {
        sched_param p{};
        p.sched_priority = priority;
        allowed = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p) == 0;
    }).join();
    return allowed;
}

// A reader late by up to 0.9 of a frame after every frame: the calibration
// still finds the bounds it finds for a punctual one (a phase measured from
// when the thread got its frame would land anywhere, and the bounds from
// phases bunched together are looser by up to a frame).
TEST(SwitchPunctuality, ALateReaderCalibratesAsTightlyAsAPunctualOne) {
    LateBench punctual(0.0), late(0.9);
    const SwitchTiming p = measure_switch_timing(*punctual.sensor, *punctual.clock);
    const SwitchTiming l = measure_switch_timing(*late.sensor, *late.clock);
    const double period = punctual.sim->timing().frame_period_s;
    EXPECT_NEAR(l.latency_max, p.latency_max, 0.02 * period);
    EXPECT_NEAR(l.clearance, p.clearance, 0.02 * period);
    EXPECT_LE(l.latency_max, SimDigitOptions{}.led_latency_s + 0.25 * period);
}

// Requests run under SCHED_FIFO when the OS allows it, and nothing else does;
// the thread leaves each request as it came. Refused, the answer says so.
TEST(SwitchPunctuality, OnlyRequestsRunInRealTime) {
    LateBench b(0.0);
    Switcher sw(*b.sensor, b.clock, measure_switch_timing(*b.sensor, *b.clock));
    EXPECT_EQ(sw.set_switch_priority(0), "normal");
    const std::string answer = sw.set_switch_priority(5);
    const bool allowed = fifo_allowed(5);
    if (allowed)
        EXPECT_EQ(answer, "fifo 5");
    else
        EXPECT_EQ(answer.rfind("normal (fifo 5 refused: ", 0), 0u) << answer;
    b.sensor->request_policies.clear();
    b.sensor->grab_policies.clear();
    const IlluminationSequence sequence = parse_sequence("15,15,15+0,15,0");
    for (int c = 0; c < 4; ++c) sw.next_cycle(sequence);
    ASSERT_GE(b.sensor->request_policies.size(), 8u);
    for (int policy : b.sensor->request_policies) EXPECT_EQ(policy, allowed ? SCHED_FIFO : SCHED_OTHER);
    for (int policy : b.sensor->grab_policies) EXPECT_EQ(policy, SCHED_OTHER);
    EXPECT_EQ(sched_getscheduler(0), SCHED_OTHER);
}

// A thread already real-time at a higher priority keeps it through a
// section (lowering it for the request would make the request the laggard).
TEST(SwitchPunctuality, AThreadAlreadyRealTimeAboveKeepsItsPriority) {
    if (!fifo_allowed(20)) GTEST_SKIP() << "SCHED_FIFO is not allowed to this process";
    int policy = -1, inside = -1, after = -1;
    std::thread([&] {
        sched_param p{};
        p.sched_priority = 20;
        pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
        sched_param q{};
        {
            const sensor::RealtimeSection section(5);
            pthread_getschedparam(pthread_self(), &policy, &q);
            inside = q.sched_priority;
        }
        pthread_getschedparam(pthread_self(), &policy, &q);
        after = q.sched_priority;
    }).join();
    EXPECT_EQ(policy, SCHED_FIFO);
    EXPECT_EQ(inside, 20);
    EXPECT_EQ(after, 20);
}

TEST(SwitchPunctuality, PrioritiesOutsideTheRangeAreRefused) {
    LateBench b(0.0);
    Switcher sw(*b.sensor, b.clock, measure_switch_timing(*b.sensor, *b.clock));
    expect_error([&] { sw.set_switch_priority(100); }, "SIM-0001", ErrorKind::InvalidArgument, "switch priority 100 (expected 0..99)");
    expect_error([&] { sw.set_switch_priority(-1); }, "SIM-0001", ErrorKind::InvalidArgument, "switch priority -1");
}

}  // namespace
}  // namespace vkfuse::test

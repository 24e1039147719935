// Sliding windows (Switcher::next_window) against the simulated DIGIT's
// ground truth: every window holds the newest clean frame of each setting,
// advances by one clean frame at a time, spans no more than window_bound, and
// is the same stream of frames the cycle schedule takes.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "sensor_doubles.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse::test {
namespace {

struct Scene {
    double latency;
    SimMotion motion;
    bool camera_auto;
    std::string sequence;
    std::string describe() const {
        return "latency " + std::to_string(latency) + ", " + std::string(to_string(motion)) +
               (camera_auto ? ", auto exposure" : "") + ", " + sequence;
    }
};

struct Simulated {
    std::shared_ptr<Clock> clock = make_virtual_clock();
    std::shared_ptr<SimDigit> sim;
    std::shared_ptr<TruthLoggingSensor> sensor;
    explicit Simulated(const Scene& s) {
        SimDigitOptions o;
        o.led_latency_s = s.latency;
        o.motion = s.motion;
        o.motion_period_s = 0.5;
        o.camera_auto = s.camera_auto;
        o.clock = clock;
        sim = std::make_shared<SimDigit>(o);
        sensor = std::make_shared<TruthLoggingSensor>(sim);
    }
};

double span_of(const std::vector<Frame>& frames) {
    const auto [lo, hi] = std::minmax_element(frames.begin(), frames.end(),
                                              [](const Frame& a, const Frame& b) { return a.timestamp < b.timestamp; });
    return hi->timestamp - lo->timestamp;
}

// A long run under tapping and sliding contacts: each frame of each window
// lit by its slot's setting alone, within the bound, and each window one
// clean frame newer than the last, the slots taking turns.
TEST(SlidingWindow, EveryWindowHoldsTheNewestCleanFrameOfEachSetting) {
    for (const Scene& s : {Scene{1.5 / 60, SimMotion::Slide, false, "15,0,0+0,15,0+0,0,15"},
                           Scene{0.08, SimMotion::Slide, false, "15,15,15+0,15,0"},
                           Scene{1.5 / 60, SimMotion::Tap, true, "15,15,15+0,15,0+0,0,15"}}) {
        SCOPED_TRACE(s.describe());
        Simulated sim(s);
        const IlluminationSequence seq = parse_sequence(s.sequence);
        const SwitchTiming timing = measure_switch_timing(*sim.sensor, *sim.clock);
        Switcher sw(*sim.sensor, sim.clock, timing);
        const double bound = window_bound(timing, seq.size());
        std::vector<Frame> last;
        std::size_t expected_new = 0;
        for (int w = 0; w < 90; ++w) {
            const std::vector<Frame> frames = sw.next_window(seq);
            ASSERT_EQ(frames.size(), seq.size());
            for (std::size_t k = 0; k < seq.size(); ++k) {
                const SimFrameTruth t = sim.sensor->truth(frames[k].index);
                ASSERT_FALSE(t.mixed) << "window " << w << " slot " << k << " frame " << frames[k].index;
                ASSERT_EQ(t.lit_by, seq[k]) << "window " << w << " slot " << k;
            }
            EXPECT_LE(span_of(frames), bound + 1e-9) << "window " << w;
            if (!last.empty()) {
                // Exactly one slot is new, the one after the last new slot.
                for (std::size_t k = 0; k < seq.size(); ++k) {
                    if (k == expected_new)
                        EXPECT_GT(frames[k].index, last[k].index) << "window " << w << " slot " << k;
                    else
                        EXPECT_EQ(frames[k].index, last[k].index) << "window " << w << " slot " << k;
                }
            }
            expected_new = (last.empty() ? 0 : expected_new + 1) % seq.size();
            last = frames;
        }
        EXPECT_EQ(sw.windows_held(), 0u);
    }
}

// The same sensor, the same schedule: windows are cycle mode's stream of
// frames, and every K-th window is a whole cycle.
TEST(SlidingWindow, EveryKthWindowIsTheCycleScheduleOfTheSameFrames) {
    const Scene setup{1.5 / 60, SimMotion::Slide, false, "15,15,15+0,15,0+0,0,15"};
    const IlluminationSequence seq = parse_sequence(setup.sequence);
    Simulated a(setup), b(setup);
    Switcher cycles(*a.sensor, a.clock, measure_switch_timing(*a.sensor, *a.clock));
    Switcher windows(*b.sensor, b.clock, measure_switch_timing(*b.sensor, *b.clock));
    for (int c = 0; c < 12; ++c) {
        const std::vector<Frame> cycle = cycles.next_cycle(seq);
        std::vector<Frame> window;
        // The first window is the first cycle; each cycle after takes K.
        for (std::size_t k = 0; k < (c == 0 ? 1 : seq.size()); ++k) window = windows.next_window(seq);
        for (std::size_t k = 0; k < seq.size(); ++k) {
            EXPECT_EQ(window[k].index, cycle[k].index) << "cycle " << c << " slot " << k;
            EXPECT_EQ(window[k].pixels, cycle[k].pixels) << "cycle " << c << " slot " << k;
        }
    }
}

// The bound is one sequence period plus the latency: for the simulator's
// two frames per setting at 60 fps and 1.5 frames of latency, 2 x 2/60 + 0.025.
TEST(SlidingWindow, TheBoundIsOneSequencePeriodPlusTheLatency) {
    SwitchTiming t;
    t.frame_period = 1.0 / 60;
    t.latency_max = 0.025;
    t.clearance = 0.0005;
    EXPECT_NEAR(window_bound(t, 2), 2 * 2.0 / 60 + 0.025, 1e-12);
    EXPECT_NEAR(window_bound(t, 3), 3 * 2.0 / 60 + 0.025, 1e-12);
    t.latency_max = 0.08;  // 5 frames from request to a whole frame
    EXPECT_NEAR(window_bound(t, 2), 2 * 5.0 / 60 + 0.08, 1e-12);
    t.latency_max = 0;
    t.clearance = -0.001;  // the latency covers the readout: one frame per setting
    EXPECT_NEAR(window_bound(t, 4), 4.0 / 60, 1e-12);
}

TEST(SlidingWindow, RecordedFramesAreReplayedAsRecordedNotWindowed) {
    Simulated sim(Scene{1.5 / 60, SimMotion::Still, false, ""});
    Switcher sw = Switcher::labelled(*sim.sensor);
    expect_error([&] { sw.next_window(parse_sequence("15,15,15+0,15,0")); }, "SIM-0001", ErrorKind::InvalidArgument,
                 "replayed as recorded");
    EXPECT_EQ(parse_fusion_window("sliding"), FusionWindow::Sliding);
    expect_error([] { parse_fusion_window("both"); }, "--window both", ErrorKind::InvalidArgument,
                 "expected cycle or sliding");
}

}  // namespace
}  // namespace vkfuse::test

// The simulated DIGIT's press motion: still, tap and slide, timed from the
// press, each frame showing the contact of its timestamp.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "expect_error.hpp"
#include "sim_support.hpp"

namespace vkfuse {
namespace {

// The camera locked (no auto exposure): a frame is then a function of its
// index, the seed and what lit and touched the gel, so two sensors can be
// compared frame by frame.
SimDigitOptions locked(const std::string& object, SimMotion motion, double period_s) {
    SimDigitOptions o;
    o.object = object;
    o.camera_auto = false;
    o.motion = motion;
    o.motion_period_s = period_s;
    return o;
}

// The phase of frame `t` in a motion of `period` started at `since`: 0 .. 1.
double phase_of(const SimFrameTruth& t, double since, double period) {
    const double cycles = (t.timestamp - since) / period;
    return cycles - std::floor(cycles);
}

TEST(SimMotion, NamesRoundTripAndBadOnesAreRefused) {
    for (SimMotion m : {SimMotion::Still, SimMotion::Tap, SimMotion::Slide})
        EXPECT_EQ(parse_sim_motion(to_string(m)), m);
    test::expect_error([] { parse_sim_motion("wiggle"); }, "--motion", ErrorKind::InvalidArgument,
                       "unknown motion \"wiggle\" (expected still, tap or slide)");
    for (double bad : {0.0, 0.049, -1.0, double(std::nan("")), double(INFINITY)}) {
        SimDigitOptions o = locked("coin", SimMotion::Tap, bad);
        test::expect_error([&] { SimDigit sim(o); }, "SIM-0001", ErrorKind::InvalidArgument, "motion period");
    }
}

// Still is what a sensor without a motion does: the same pixels, frame by frame.
TEST(SimMotion, StillKeepsThePressAsItWas) {
    SimDigit still(locked("screw", SimMotion::Still, 0.1));
    SimDigitOptions plain_options = locked("screw", SimMotion::Still, 2.0);
    SimDigit plain(plain_options);
    for (int i = 0; i < 10; ++i) {
        const Frame a = still.grab(), b = plain.grab();
        EXPECT_EQ(a.pixels, b.pixels) << "frame " << i;
        const SimFrameTruth t = still.truth(a.index);
        EXPECT_EQ(t.object, "screw");
        EXPECT_EQ(t.contact_x, 0.5);
        EXPECT_EQ(t.contact_y, 0.5);
    }
}

// Tap: pressed for the first half of each period, then the untouched gel -
// the very frame a sensor with nothing pressed takes.
TEST(SimMotion, TapPressesForHalfOfEachPeriod) {
    const double period = 0.21;  // 12.6 frames at 60 fps: no frame starts on a half period
    SimDigit tap(locked("coin", SimMotion::Tap, period));
    SimDigit bare(locked("nothing", SimMotion::Still, period));
    SimDigit pressed(locked("coin", SimMotion::Still, period));
    int touching = 0, lifted = 0;
    for (int i = 0; i < 36; ++i) {
        const Frame f = tap.grab(), b = bare.grab(), p = pressed.grab();
        const SimFrameTruth t = tap.truth(f.index);
        const bool first_half = phase_of(t, tap.truth(0).timestamp, period) < 0.5;
        if (first_half) {
            EXPECT_EQ(t.object, "coin-heads") << "frame " << i;
            EXPECT_EQ(f.pixels, p.pixels) << "frame " << i;
            ++touching;
        } else {
            EXPECT_EQ(t.object, "nothing") << "frame " << i;
            EXPECT_EQ(f.pixels, b.pixels) << "frame " << i;
            ++lifted;
        }
    }
    EXPECT_GE(touching, 17);  // 36 frames over 2.86 periods
    EXPECT_GE(lifted, 17);
}

// Slide: the centre walks 0.25 -> 0.75 -> 0.25 of the width in steps of 1/16
// once per period, y where it was pressed, and the pixels move with it.
TEST(SimMotion, SlideCrossesTheGelAndComesBack) {
    const double period = 0.3;  // 18 frames
    SimDigitOptions o = locked("screw", SimMotion::Slide, period);
    o.y = 0.4;
    SimDigit slide(o);
    std::set<double> xs;
    double previous_x = -1;
    std::vector<std::uint8_t> previous_pixels;
    for (int i = 0; i < 18; ++i) {
        const Frame f = slide.grab();
        const SimFrameTruth t = slide.truth(f.index);
        const double phase = phase_of(t, slide.truth(0).timestamp, period);
        const double out_and_back = phase < 0.5 ? 2 * phase : 2 - 2 * phase;
        EXPECT_NEAR(t.contact_x, 0.25 + std::round(out_and_back * 8) / 16, 1e-12) << "frame " << i;
        EXPECT_EQ(t.contact_y, 0.4);
        EXPECT_EQ(t.object, "screw");
        EXPECT_EQ(std::fmod((t.contact_x - 0.25) * 16, 1.0), 0.0) << t.contact_x;
        if (t.contact_x != previous_x && !previous_pixels.empty()) {
            EXPECT_NE(f.pixels, previous_pixels) << "frame " << i << ": the contact moved, the image did not";
        }
        previous_x = t.contact_x;
        previous_pixels = f.pixels;
        xs.insert(t.contact_x);
    }
    EXPECT_EQ(*xs.begin(), 0.25);
    EXPECT_EQ(*xs.rbegin(), 0.75);
    EXPECT_GE(xs.size(), 8u);
}

// render() gives a grabbed frame back byte for byte from its index, the
// setting that lit it and its own instant, and at another instant shows that
// instant's contact under the same noise: the frames a sliding window's
// same-moment reference is fused from.
TEST(SimMotion, RenderGivesAGrabbedFrameBackAndOtherInstantsTheirContact) {
    const double period = 0.3;
    SimDigit slide(locked("screw", SimMotion::Slide, period));
    const Illumination setting = Illumination::parse("0,15,0");
    slide.set_illumination(setting);
    std::vector<Frame> frames;
    for (int i = 0; i < 12; ++i) frames.push_back(slide.grab());
    for (std::size_t i = 4; i < frames.size(); ++i) {  // past the switch from the power-on setting
        const Frame& f = frames[i];
        ASSERT_FALSE(slide.truth(f.index).mixed);
        EXPECT_EQ(slide.render(f.index, setting, f.timestamp).pixels, f.pixels) << "frame " << f.index;
        // The contact of frame i - 4 (another slide position), on frame i's noise.
        const Frame earlier = slide.render(f.index, setting, frames[i - 4].timestamp);
        const bool moved = slide.truth(frames[i - 4].index).contact_x != slide.truth(f.index).contact_x;
        EXPECT_EQ(earlier.pixels != f.pixels, moved) << "frame " << f.index;
    }
    test::expect_error([&] { slide.render(0, Illumination::parse("16,0,0"), 0); }, "SIM-0001", ErrorKind::InvalidArgument,
                 "16");
}

// A press (set_object) starts the motion over: its first frame is pressed.
TEST(SimMotion, SetObjectStartsTheMotionOver) {
    const double period = 0.2;
    SimDigit tap(locked("nothing", SimMotion::Tap, period));
    for (int i = 0; i < 7; ++i) EXPECT_EQ(tap.truth(tap.grab().index).object, "nothing");
    tap.set_object("lego");
    const Frame first = tap.grab();
    const SimFrameTruth t = tap.truth(first.index);
    EXPECT_EQ(t.object, "lego");
    int pressed = 1;
    for (int i = 0; i < 11; ++i) pressed += tap.truth(tap.grab().index).object == "lego";
    EXPECT_GE(pressed, 5);  // about half of 12 frames
    EXPECT_LE(pressed, 7);
}

}  // namespace
}  // namespace vkfuse

// The simulated camera's auto exposure and white balance after an LED switch.
#include <gtest/gtest.h>

#include "sim_support.hpp"

namespace vkfuse {
namespace {

TEST(SimIsp, GreenAloneIsBroughtBackToTheSameBrightness) {
    SimDigitOptions o;
    o.object = "nothing";
    SimDigit sim(o);
    const Frame white = test::settle(sim, Illumination({15, 15, 15}));
    const Frame green = test::settle(sim, Illumination({0, 15, 0}));
    auto luma = [](const Frame& f) {
        const auto m = test::channel_means(test::to_image(f));
        return 0.299 * m[0] + 0.587 * m[1] + 0.114 * m[2];
    };
    EXPECT_NEAR(luma(green), luma(white), 0.02 * luma(white));
    const SimFrameTruth t = sim.truth(green.index);
    EXPECT_GT(t.exposure_s, sim.truth(white.index).exposure_s * 1.2);  // a third of the light came back
    // White balance pulls red and blue toward grey, as far as its range goes.
    EXPECT_GT(t.white_balance[0], 2.0);
    EXPECT_GT(t.white_balance[2], 2.0);
    EXPECT_DOUBLE_EQ(t.white_balance[1], 1.0);
    // Back to white, the camera returns to where it started: no memory.
    const Frame again = test::settle(sim, Illumination({15, 15, 15}));
    EXPECT_TRUE(test::same_readout(sim.truth(again.index), sim.truth(white.index), 1e-3));
}

// The paper: frames taken less than 0.1 s after a switch were unusable. Here
// the LED latency, the rolling exposure and a few frames of auto exposure
// and white balance add up to about that.
TEST(SimIsp, ASwitchSettlesInAboutATenthOfASecond) {
    SimDigitOptions o;
    o.object = "nothing";
    SimDigit sim(o);
    test::settle(sim, Illumination({15, 15, 15}));
    int frames = 0;
    test::settle(sim, Illumination({0, 15, 0}), &frames);
    const double seconds = frames / sim.info().fps;
    EXPECT_GT(seconds, 0.06);
    EXPECT_LT(seconds, 0.2);
}

TEST(SimIsp, WithoutItTheReadoutIsFixed) {
    SimDigitOptions o;
    o.object = "nothing";
    o.camera_auto = false;
    SimDigit sim(o);
    const Frame green = test::settle(sim, Illumination({0, 15, 0}));
    const SimFrameTruth t = sim.truth(green.index);
    EXPECT_DOUBLE_EQ(t.exposure_s, sim.timing().nominal_exposure_s);
    EXPECT_DOUBLE_EQ(t.analog_gain, 1.0);
    EXPECT_EQ(t.white_balance, (std::array<double, 3>{1, 1, 1}));
}

}  // namespace
}  // namespace vkfuse

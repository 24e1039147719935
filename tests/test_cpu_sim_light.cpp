// The simulated DIGIT's LEDs and camera: levels, crosstalk, darkness, saturation.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_support.hpp"

namespace vkfuse {
namespace {

// Raw physics: fixed exposure and unity gains, so frames show the light itself.
SimDigitOptions raw(const std::string& object = "nothing") {
    SimDigitOptions o;
    o.object = object;
    o.camera_auto = false;
    return o;
}

TEST(SimLight, EachLevelStepAddsLightToItsChannel) {
    SimDigit sim(raw());
    for (int led = 0; led < 3; ++led) {
        double previous = -1;
        for (int level : {0, 1, 5, 10, 15}) {
            std::vector<int> levels{0, 0, 0};
            levels[std::size_t(led)] = level;
            const auto means = test::channel_means(test::to_image(test::settle(sim, Illumination(levels))));
            EXPECT_GT(means[std::size_t(led)], previous) << "LED " << led << " level " << level;
            previous = means[std::size_t(led)];
        }
        // Linear in the level: full is three times a third (within noise and rounding).
        std::vector<int> third{0, 0, 0}, full{0, 0, 0};
        third[std::size_t(led)] = 5;
        full[std::size_t(led)] = 15;
        const double a = test::channel_means(test::to_image(test::settle(sim, Illumination(third))))[std::size_t(led)];
        const double b = test::channel_means(test::to_image(test::settle(sim, Illumination(full))))[std::size_t(led)];
        EXPECT_NEAR(b / a, 3.0, 0.05) << "LED " << led;
    }
}

TEST(SimLight, OneLedLightsItsChannelAndLeaksIntoTheOthers) {
    SimDigit sim(raw());
    const auto green = test::channel_means(test::to_image(test::settle(sim, Illumination({0, 15, 0}))));
    EXPECT_GT(green[1], 50.0);
    // Colour filters overlap: some green light reads as blue, a little as red.
    EXPECT_GT(green[2], 0.1 * green[1]);
    EXPECT_LT(green[2], 0.5 * green[1]);
    EXPECT_GT(green[0], 0.03 * green[1]);
    EXPECT_LT(green[0], green[2]);
    // Light adds up: the three single-LED frames sum to the white frame.
    const auto red = test::channel_means(test::to_image(test::settle(sim, Illumination({15, 0, 0}))));
    const auto blue = test::channel_means(test::to_image(test::settle(sim, Illumination({0, 0, 15}))));
    const auto white = test::channel_means(test::to_image(test::settle(sim, Illumination({15, 15, 15}))));
    for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(red[c] + green[c] + blue[c], white[c], 1.0) << "channel " << c;
}

TEST(SimLight, AllLedsOffIsBlackButForReadNoise) {
    SimDigit sim(raw());
    const Frame dark = test::settle(sim, Illumination({0, 0, 0}));
    double sum = 0, sum2 = 0;
    for (std::uint8_t v : dark.pixels) {
        sum += v;
        sum2 += double(v) * v;
    }
    const double n = double(dark.pixels.size());
    // Read noise of 0.5 DN around 0, clipped at 0 and rounded: mostly 0, some 1s.
    EXPECT_LT(sum / n, 0.5);
    EXPECT_GT(sum / n, 0.01);
    EXPECT_LT(std::sqrt(sum2 / n), 1.0);
    EXPECT_LE(*std::max_element(dark.pixels.begin(), dark.pixels.end()), 4);
}

TEST(SimLight, AutoExposureCannotLiftBlackAboveAmplifiedReadNoise) {
    SimDigitOptions o;
    o.object = "nothing";
    SimDigit sim(o);
    const Frame dark = test::settle(sim, Illumination({0, 0, 0}));
    const SimFrameTruth t = sim.truth(dark.index);
    EXPECT_DOUBLE_EQ(t.exposure_s, sim.timing().max_exposure_s);  // it tried its hardest
    EXPECT_GT(t.analog_gain, 1.0);
    const auto means = test::channel_means(test::to_image(dark));
    for (double m : means) EXPECT_LT(m, 3.0);
}

TEST(SimLight, BrightSlopesSaturateAt255) {
    SimDigit sim(raw("coin-heads"));
    const Frame f = test::settle(sim, Illumination({15, 15, 15}));
    std::size_t clipped = 0;
    for (std::size_t i = 0; i < f.pixels.size(); i += 3) clipped += f.pixels[i] == 255;
    // The rim facing the red LED is lit steeply enough to clip; the flat gel is not.
    EXPECT_GT(clipped, 50u);
    EXPECT_LT(clipped, f.pixels.size() / 3 / 10);
}

}  // namespace
}  // namespace vkfuse

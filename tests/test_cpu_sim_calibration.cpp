// The simulated gel background against a real DIGIT frame (tests/data/digit_bg_tacto.png).
#include <gtest/gtest.h>

#include <cmath>

#include "sim/calibration.hpp"
#include "sim_support.hpp"
#include "test_support.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse {
namespace {

// The real frame as the sensor streams it (landscape 320x240).
ImageD real_frame() {
    return sim::landscape_from_portrait(convert<double>(io::read_image(test::data_path("digit_bg_tacto.png"))));
}

ImageD simulated_background() {
    SimDigitOptions o;
    o.object = "nothing";
    SimDigit sim(o);
    return test::to_image(test::settle(sim, Illumination({15, 15, 15})));
}

TEST(SimCalibration, PortraitToLandscapeUndoesDigitInterface) {
    // digit_interface: portrait = flip(transpose(landscape), vertical).
    ImageD land(2, 3, 1);
    for (std::size_t i = 0; i < land.data.size(); ++i) land.data[i] = double(i);
    ImageD portrait(3, 2, 1);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 2; ++j) portrait.at(i, j, 0) = land.at(j, 2 - i, 0);
    EXPECT_EQ(sim::landscape_from_portrait(portrait).data, land.data);
}

TEST(SimCalibration, BackgroundMeansMatchTheRealFrame) {
    const auto real = test::channel_means(real_frame());
    const auto sim = test::channel_means(simulated_background());
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sim[std::size_t(c)], real[std::size_t(c)], 15.0) << "channel " << c;
}

// The low-frequency structure (8x8 block means, 40x30 per channel) follows
// the real frame's colour gradients. 0.9: the calibrated fields are cubic
// polynomials fitted to that frame (correlation about 0.95 per channel), a
// mirrored or rotated frame scores below 0.5, and noise moves it by < 0.01.
TEST(SimCalibration, BackgroundGradientsCorrelateWithTheRealFrame) {
    const ImageD real = real_frame(), sim = simulated_background();
    for (int c = 0; c < 3; ++c) {
        const double r = test::correlation(test::block_means(sim, c), test::block_means(real, c));
        EXPECT_GT(r, 0.9) << "channel " << c;
    }
    // The orientation matters: the same frame upside down does not match.
    ImageD flipped = real;
    for (int y = 0; y < real.height; ++y)
        for (int x = 0; x < real.width; ++x)
            for (int c = 0; c < 3; ++c) flipped.at(y, x, c) = real.at(real.height - 1 - y, real.width - 1 - x, c);
    double worst = 1;
    for (int c = 0; c < 3; ++c)
        worst = std::min(worst, test::correlation(test::block_means(sim, c), test::block_means(flipped, c)));
    EXPECT_LT(worst, 0.5);
}

TEST(SimCalibration, StoredLightFieldsAreTheLeastSquaresFit) {
    const sim::LedRig rig = sim::digit_led_rig();
    const auto fitted = sim::fit_light_fields(real_frame(), rig.crosstalk);
    for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t j = 0; j < fitted[k].size(); ++j)
            EXPECT_NEAR(rig.leds[k].field[j], fitted[k][j], 1e-3 * (1 + std::abs(fitted[k][j]))) << "LED " << k << " term " << j;
}

// Pixel noise: the real frame's deviation from its 3x3 local mean is about
// 0.6-0.9 DN; the simulation should be the same order (it also has the
// JPEG-free shot and read noise of the camera), within a factor of two.
TEST(SimCalibration, FineScaleNoiseIsLikeTheRealFrame) {
    auto local_noise = [](const ImageD& img) {
        double sum = 0;
        long n = 0;
        for (int y = 1; y + 1 < img.height; ++y)
            for (int x = 1; x + 1 < img.width; ++x)
                for (int c = 0; c < 3; ++c) {
                    double local = 0;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) local += img.at(y + dy, x + dx, c) / 9.0;
                    const double d = 255.0 * (img.at(y, x, c) - local);
                    sum += d * d;
                    ++n;
                }
        return std::sqrt(sum / double(n));
    };
    const double real = local_noise(real_frame()), sim = local_noise(simulated_background());
    EXPECT_GT(sim, real / 2);
    EXPECT_LT(sim, real * 2);
}

}  // namespace
}  // namespace vkfuse

// The simulated DIGIT: stream geometry, timestamps, and determinism for a seed.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_support.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse {
namespace {

std::vector<Frame> grab_frames(const SimDigitOptions& options, int count) {
    SimDigit sim(options);
    std::vector<Frame> frames;
    for (int i = 0; i < count; ++i) frames.push_back(sim.grab());
    return frames;
}

TEST(SimDigit, StreamsQvgaAt60AndVgaAt30Landscape) {
    SimDigit qvga;
    const SensorInfo q = qvga.info();
    EXPECT_EQ(q.model, "DIGIT (simulated)");
    EXPECT_EQ(q.serial, "SIM-0001");
    EXPECT_EQ(q.width, 320);
    EXPECT_EQ(q.height, 240);
    EXPECT_DOUBLE_EQ(q.fps, 60.0);
    EXPECT_EQ(q.leds.channels, 3);
    const Frame f = qvga.grab();
    EXPECT_EQ(f.width, 320);
    EXPECT_EQ(f.height, 240);
    EXPECT_EQ(f.pixels.size(), 320u * 240u * 3u);

    SimDigitOptions o;
    o.vga = true;
    o.object = "ball";
    SimDigit vga(o);
    EXPECT_EQ(vga.info().width, 640);
    EXPECT_EQ(vga.info().height, 480);
    EXPECT_DOUBLE_EQ(vga.info().fps, 30.0);
    EXPECT_EQ(vga.grab().pixels.size(), 640u * 480u * 3u);
}

TEST(SimDigit, VirtualTimestampsAreFrameIndexOverFps) {
    SimDigit sim;
    for (std::uint64_t n = 0; n < 5; ++n) {
        const Frame f = sim.grab();
        EXPECT_EQ(f.index, n);
        EXPECT_DOUBLE_EQ(f.timestamp, double(n) / 60.0);
        // Like a real DIGIT, the frame does not say what lit it.
        EXPECT_FALSE(f.illumination.has_value());
    }
}

TEST(SimDigit, SameSeedGivesBitIdenticalFrames) {
    SimDigitOptions o;
    o.seed = 42;
    o.object = "coin-tails";
    const auto a = grab_frames(o, 3), b = grab_frames(o, 3);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].pixels, b[i].pixels) << "frame " << i;
        EXPECT_EQ(a[i].timestamp, b[i].timestamp);
    }
    EXPECT_NE(a[0].pixels, a[1].pixels);  // noise is fresh every frame
}

TEST(SimDigit, OtherSeedsDifferOnlyByNoise) {
    SimDigitOptions o;
    o.object = "lego";
    const Frame a = grab_frames(o, 1)[0];
    o.seed = 7;
    const Frame b = grab_frames(o, 1)[0];
    ASSERT_NE(a.pixels, b.pixels);
    // The difference of two independent noise draws: zero mean, a spread of
    // sqrt(2) x the per-pixel noise (about 1.1 DN at these levels), no outliers
    // beyond what Gaussian noise gives, no structure.
    double sum = 0, sum2 = 0, worst = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const double d = double(a.pixels[i]) - double(b.pixels[i]);
        sum += d;
        sum2 += d * d;
        worst = std::max(worst, std::abs(d));
    }
    const double n = double(a.pixels.size());
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_LT(std::abs(mean), 0.02);
    EXPECT_GT(sd, 0.8);
    EXPECT_LT(sd, 2.5);
    EXPECT_LE(worst, 12.0);
    // No structure: the difference averaged over 8x8 blocks is flat.
    const ImageD da = test::to_image(a), db = test::to_image(b);
    for (int c = 0; c < 3; ++c) {
        const auto ba = test::block_means(da, c), bb = test::block_means(db, c);
        for (std::size_t i = 0; i < ba.size(); ++i) ASSERT_NEAR(ba[i], bb[i], 1.5) << "block " << i;
    }
}

}  // namespace
}  // namespace vkfuse

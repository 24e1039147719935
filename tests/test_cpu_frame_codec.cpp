// What a UVC camera sends, to RGB: YUYV against the BT.601 limited-range
// formulas, Motion-JPEG against the image it was encoded from, and damaged
// frames refused, never papered over.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "sensor/frame_codec.hpp"

namespace vkfuse::test {
namespace {

// A smooth test card: gradients in every channel, as a gel image is smooth.
std::vector<std::uint8_t> card(int width, int height) {
    std::vector<std::uint8_t> rgb(std::size_t(width) * std::size_t(height) * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
            p[0] = std::uint8_t(40 + 170 * x / width);
            p[1] = std::uint8_t(30 + 190 * y / height);
            p[2] = std::uint8_t(200 - 150 * (x + y) / (width + height));
        }
    return rgb;
}

double rms_difference(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    return std::sqrt(sum / double(a.size()));
}

TEST(FrameCodec, YuyvFollowsTheLimitedRangeFormulas) {
    // Two pixels per macropixel; Y U Y V. Video black, white, and a saturated red.
    const std::vector<std::uint8_t> yuyv = {16, 128, 235, 128, 81, 90, 81, 240};
    std::vector<std::uint8_t> rgb;
    ASSERT_TRUE(yuyv_to_rgb(yuyv, 4, 1, rgb));
    ASSERT_EQ(rgb.size(), 12u);
    const std::uint8_t black[3] = {0, 0, 0}, white[3] = {255, 255, 255};
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(rgb[std::size_t(c)], black[c]);
        EXPECT_EQ(rgb[std::size_t(3 + c)], white[c]);
    }
    for (int k = 2; k < 4; ++k) {
        // Y 81, U 90, V 240: R = 1.164*65 + 1.596*112 = 254.4, G = 75.7 + 14.9 - 91.1 = -0.5, B = 75.7 - 76.6 = -0.9
        EXPECT_NEAR(rgb[std::size_t(3 * k)], 254, 1);
        EXPECT_LE(rgb[std::size_t(3 * k + 1)], 1);
        EXPECT_LE(rgb[std::size_t(3 * k + 2)], 1);
    }
}

TEST(FrameCodec, YuyvRoundTripKeepsASmoothImage) {
    const int w = 64, h = 48;
    const std::vector<std::uint8_t> rgb = card(w, h);
    const std::vector<std::uint8_t> yuyv = rgb_to_yuyv(rgb, w, h);
    ASSERT_EQ(yuyv.size(), std::size_t(w * h * 2));
    std::vector<std::uint8_t> back;
    ASSERT_TRUE(yuyv_to_rgb(yuyv, w, h, back));
    EXPECT_LT(rms_difference(rgb, back), 2.0);
}

TEST(FrameCodec, ShortOrOddYuyvIsRefused) {
    std::vector<std::uint8_t> rgb;
    EXPECT_FALSE(yuyv_to_rgb(std::vector<std::uint8_t>(4 * 2 * 2 - 1), 4, 2, rgb));
    EXPECT_FALSE(yuyv_to_rgb(std::vector<std::uint8_t>(3 * 2 * 2), 3, 2, rgb));
}

TEST(FrameCodec, MjpegDecodesToTheImageItWasMadeFrom) {
    const int w = 320, h = 240;
    const std::vector<std::uint8_t> rgb = card(w, h);
    const std::vector<std::uint8_t> jpeg = rgb_to_jpeg(rgb, w, h, 90);
    ASSERT_GT(jpeg.size(), 100u);
    std::vector<std::uint8_t> back;
    std::string why;
    ASSERT_TRUE(mjpeg_to_rgb(jpeg, w, h, back, why)) << why;
    EXPECT_LT(rms_difference(rgb, back), 3.0);
}

TEST(FrameCodec, DamagedMjpegIsRefusedWithAReason) {
    const int w = 320, h = 240;
    const std::vector<std::uint8_t> jpeg = rgb_to_jpeg(card(w, h), w, h, 90);
    std::vector<std::uint8_t> rgb;
    std::string why;
    // Cut short: libjpeg would fill the rest with grey and only warn.
    const std::vector<std::uint8_t> cut(jpeg.begin(), jpeg.begin() + std::ptrdiff_t(jpeg.size() / 2));
    EXPECT_FALSE(mjpeg_to_rgb(cut, w, h, rgb, why));
    EXPECT_FALSE(why.empty());
    // Not a JPEG at all.
    why.clear();
    EXPECT_FALSE(mjpeg_to_rgb(std::vector<std::uint8_t>(1000, 0x55), w, h, rgb, why));
    EXPECT_EQ(why, "not a JPEG frame");
    // A good frame of another size than negotiated.
    why.clear();
    EXPECT_FALSE(mjpeg_to_rgb(jpeg, 640, 480, rgb, why));
    EXPECT_NE(why.find("320x240"), std::string::npos) << why;
    // Its header broken after the start marker.
    std::vector<std::uint8_t> broken = jpeg;
    for (std::size_t i = 2; i < 40; ++i) broken[i] = 0xFF;
    why.clear();
    EXPECT_FALSE(mjpeg_to_rgb(broken, w, h, rgb, why));
    EXPECT_FALSE(why.empty());
}

}  // namespace
}  // namespace vkfuse::test

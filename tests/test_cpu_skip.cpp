// The CPU twin of change detection (core/skip.hpp), by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "expect_error.hpp"
#include "vkfuse/core/skip.hpp"

namespace vkfuse::test {
namespace {

TEST(SkipPolicyNames, RoundTrip) {
    for (SkipPolicy p : {SkipPolicy::Off, SkipPolicy::Idle, SkipPolicy::Static}) EXPECT_EQ(parse_skip_policy(to_string(p)), p);
    EXPECT_FALSE(parse_skip_policy("tile"));
    EXPECT_FALSE(parse_skip_policy(""));
}

TEST(BackgroundDeviation, IsTheSampleStandardDeviation) {
    const std::vector<std::uint8_t> a = {0, 10}, b = {255, 20};
    Image mean(1, 2, 1);
    mean.data = {127.5f / 255, 15.0f / 255};
    const std::vector<FrameView> frames = {{a.data(), 1, 2, 1, PixelType::U8}, {b.data(), 1, 2, 1, PixelType::U8}};
    const Image dev = background_deviation(frames, mean);
    EXPECT_NEAR(dev.data[0], std::sqrt(2 * 127.5 * 127.5) / 255, 1e-6);
    EXPECT_NEAR(dev.data[1], std::sqrt(2 * 5.0 * 5.0) / 255, 1e-6);
    EXPECT_EQ(background_deviation(std::span(frames).first(1), mean).data, std::vector<float>(2, 0.0f));
}

// 40 x 33 frames: tiles of 32 leave a 8-wide and a 1-tall edge.
TEST(ChangeScores, AreTheLargestDeviationInNoiseUnitsPerTile) {
    const int h = 33, w = 40;
    SkipReference r;
    for (int k = 0; k < 2; ++k) {
        Image mean(h, w, 1), dev(h, w, 1);
        for (float& v : mean.data) v = 0.5f;
        for (float& v : dev.data) v = 0.01f * float(k + 1);
        r.mean.push_back(mean);
        r.deviation.push_back(dev);
    }
    for (int x = 32; x < w; ++x) r.deviation[0].at(32, x, 0) = 0.0f;  // the 8 x 1 corner tile: noise floored
    EXPECT_EQ(skip_tiles_x(w), 2);
    EXPECT_EQ(skip_tiles_y(h), 2);
    const std::vector<float> noise = tile_noise(r);
    ASSERT_EQ(noise.size(), 8u);
    EXPECT_FLOAT_EQ(noise[0], float(0.01f * kMeanSteps));  // in steps of 1/256 of an 8-bit level
    EXPECT_FLOAT_EQ(noise[4], float(0.02f * kMeanSteps));
    EXPECT_EQ(noise[3], 128.0f);  // the floor, half a level, exactly
    Image f0(h, w, 1), f1(h, w, 1);
    for (float& v : f0.data) v = 0.5f;
    f1 = f0;
    f0.at(3, 35, 0) = 0.55f;  // tile 1, setting 0: 0.05 / 0.01 = 5
    f1.at(3, 36, 0) = 0.38f;  // tile 1, setting 1: 0.12 / 0.02 = 6
    f1.at(32, 0, 0) = 0.51f;  // tile 2, setting 1: 0.5
    const std::vector<FrameView> frames = {FrameView::of(f0), FrameView::of(f1)};
    const std::vector<double> s = change_scores_reference(frames, r);
    ASSERT_EQ(s.size(), 4u);
    EXPECT_NEAR(s[0], 0.0, 1e-12);
    EXPECT_NEAR(s[1], 6.0, 1e-5);
    EXPECT_NEAR(s[2], 0.5, 1e-5);
    EXPECT_NEAR(s[3], 0.0, 1e-12);
}

// Against the previous frames, in units of the noise of a difference of
// two frames: sqrt 2 times the tile's.
TEST(StaticScores, AreTheLargestChangeSinceThePreviousFrames) {
    SkipReference r;
    Image mean(4, 40, 1), dev(4, 40, 1);
    for (float& v : dev.data) v = 0.01f;
    r.mean = {mean};
    r.deviation = {dev};
    Image now(4, 40, 1), before(4, 40, 1);
    for (float& v : now.data) v = 0.4f;
    before = now;
    before.at(2, 35, 0) = 0.43f;  // tile 1
    const std::vector<FrameView> a = {FrameView::of(now)}, b = {FrameView::of(before)};
    const std::vector<double> s = static_scores_reference(a, b, r);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0], 0.0);
    EXPECT_NEAR(s[1], 0.03 / (0.01 * std::sqrt(2.0)), 1e-5);
}

TEST(SkipReferenceCheck, NamesWhatIsWrong) {
    SkipReference r;
    r.mean.assign(2, Image(4, 4, 3));
    r.deviation.assign(2, Image(4, 4, 3));
    check_skip_reference(r, 4, 4, 3, 2, "ref");
    expect_error([&] { check_skip_reference(r, 4, 5, 3, 2, "ref"); }, "ref", ErrorKind::Shape, "an image of 4x4x3");
    expect_error([&] { check_skip_reference(r, 4, 4, 3, 3, "ref"); }, "ref", ErrorKind::InvalidArgument,
                 "2 means and 2 deviations for 3 frames");
}

}  // namespace
}  // namespace vkfuse::test

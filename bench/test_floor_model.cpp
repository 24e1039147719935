// The floor model's counts against access counts derived by hand, pass by
// pass, from the ideal pipelines drawn in floor_model.cpp, and its pricing
// against the probe.
#include <gtest/gtest.h>

#include "floor_model.hpp"

namespace vkfuse::bench {
namespace {

Cell cell(Method m, int levels, int sensors, Size size = {320, 240}, int frames = 3, Wavelet w = Wavelet::Bior44) {
    Cell c;
    c.method.method = m;
    c.method.wavelet = w;
    c.levels = levels;
    c.size = size;
    c.frames = frames;
    c.sensors = sensors;
    return c;
}

double per_input_sample(const Cell& c, bool eight_bit = false) {
    return ideal_pipeline(c, eight_bit).accesses / (double(c.size.width) * c.size.height * 3 * c.frames);
}

// QVGA, K = 3, in units of n = H W C (the frames are 3 n; the metrics read
// the image and the background, 2 n).
TEST(FloorModel, AccessesPerInputSampleAtQvga) {
    // Pointwise: frames 3 n, image 1 n, metrics 2 n; channel-sum reads one
    // channel of each frame (1 n).
    EXPECT_NEAR(per_input_sample(cell(Method::Brovey, 0, 1)), 6.0 / 3, 1e-12);
    EXPECT_NEAR(per_input_sample(cell(Method::ChannelSum, 0, 1)), 4.0 / 3, 1e-12);
    // Laplacian L4: per level, pyrDown 3 + 0.75, fuse and collapse 3 + 0.75
    // + 0.25 (R_{l+1}) + 1 (R_l): 8.75 n_l, over 1 + 1/4 + 1/16 + 1/64 =
    // 85/64; the base rule 3/256 + 1/256; metrics 2. 13.64 n: 4.55 per input
    // sample.
    EXPECT_NEAR(per_input_sample(cell(Method::Laplacian, 4, 1)), (8.75 * 85 / 64 + 4.0 / 256 + 2) / 3, 1e-12);
    // Wavelet L3: level 0 rows 3 + 3, columns 3 + 0.75 (details) + 0.75 (A_1
    // of each frame), inverse 1 + 2 + 1: 14.5 n; level 1 a quarter of that;
    // level 2 rows 6/16, columns (3 + 1)/16 (the fused approximation instead
    // of each frame's), inverse 4/16; metrics 2. 21 n: 7.0 per input sample.
    EXPECT_NEAR(per_input_sample(cell(Method::Wavelet, 3, 1)), 7.0, 1e-12);
}

TEST(FloorModel, EightBitFramesAreReadAsWordsOfFour) {
    // The wavelet reads the frames once (its level-0 row pass), the
    // Laplacian twice (pyrDown and the fusion of level 0).
    EXPECT_NEAR(per_input_sample(cell(Method::Wavelet, 3, 1)) - per_input_sample(cell(Method::Wavelet, 3, 1), true),
                0.75, 1e-12);
    EXPECT_NEAR(per_input_sample(cell(Method::Laplacian, 4, 1)) - per_input_sample(cell(Method::Laplacian, 4, 1), true),
                1.5, 1e-12);
    // Issue 4 estimated 6.7 (wavelet L3) and 4.9 (Laplacian L4) from 8-bit
    // frames, counting 3 n for the metric pass and an 8-bit pack besides;
    // pass by pass the ideal pipelines need 6.25 and 3.05.
    EXPECT_NEAR(per_input_sample(cell(Method::Wavelet, 3, 1), true), 6.25, 1e-12);
    EXPECT_NEAR(per_input_sample(cell(Method::Laplacian, 4, 1), true), (8.75 * 85 / 64 + 4.0 / 256 + 2) / 3 - 1.5,
                1e-12);
}

TEST(FloorModel, OddSizesCountTheirPaddedLevels) {
    // 5 x 3 RGB, K = 2: n_0 = 45, level 1 is 3 x 2 (n_1 = 18).
    // Wavelet L1 (periodization): rows 90 + 2 * 54 (3 rows of 6 padded
    // columns), columns 108 + 54 details + 18 fused approximation, inverse
    // 72 + 2 * 54 + 45, metrics 90.
    EXPECT_DOUBLE_EQ(ideal_pipeline(cell(Method::Wavelet, 1, 1, {5, 3}, 2), false).accesses,
                     198 + 180 + 225 + 90);
    // Laplacian L1: pyrDown 90 + 36, the base rule 36 + 18 (R_1), fuse and
    // collapse 90 + 36 + 18 + 45, metrics 90.
    EXPECT_DOUBLE_EQ(ideal_pipeline(cell(Method::Laplacian, 1, 1, {5, 3}, 2), false).accesses,
                     126 + 54 + 189 + 90);
}

TEST(FloorModel, WaveletArithmeticTakesTheNonzeroTaps) {
    // 4 x 2 RGB, K = 2, L1: n_0 = 24, rows r = 24, block 24. Haar: 2 taps per
    // output. Rows and columns 2 * 2 * 2 * (24 + 24), the rule 2 * 2 * 24,
    // the inverse 2 * 2 * (24 + 24), the metrics 30 * 8 pixels.
    const Cell haar = cell(Method::Wavelet, 1, 1, {4, 2}, 2, Wavelet::Haar);
    EXPECT_DOUBLE_EQ(ideal_pipeline(haar, false).flops, 384 + 96 + 192 + 240);
    // bior4.4: 8 nonzero taps per output on average (pywt pads to 10), 6 more
    // than haar on each of 96 analysis and 48 synthesis outputs.
    const Cell bior = cell(Method::Wavelet, 1, 1, {4, 2}, 2, Wavelet::Bior44);
    EXPECT_DOUBLE_EQ(ideal_pipeline(bior, false).flops - ideal_pipeline(haar, false).flops, 2 * 6 * (96 + 48));
}

TEST(FloorModel, WorkGrowsWithSensorsAndDispatchesDoNot) {
    for (Method m : {Method::ChannelSum, Method::Laplacian, Method::Wavelet}) {
        const int L = m == Method::ChannelSum ? 0 : 3;
        const PipelineCost one = ideal_pipeline(cell(m, L, 1), false), many = ideal_pipeline(cell(m, L, 64), false);
        EXPECT_NEAR(many.accesses, 64 * one.accesses, 1e-9 * many.accesses);
        EXPECT_NEAR(many.flops, 64 * one.flops, 1e-9 * many.flops);
        EXPECT_EQ(many.dispatches, one.dispatches);
    }
    // Passes: fuse + metrics; pyrDown and fuse-and-collapse per level, the
    // base rule + metrics; rows, columns, inverse columns, inverse rows per
    // level + metrics.
    EXPECT_EQ(ideal_pipeline(cell(Method::Brovey, 0, 1), false).dispatches, 2);
    EXPECT_EQ(ideal_pipeline(cell(Method::Laplacian, 4, 1), false).dispatches, 10);
    EXPECT_EQ(ideal_pipeline(cell(Method::Wavelet, 3, 1), false).dispatches, 13);
}

TEST(FloorModel, PricedAtTheProbedCosts) {
    vk::KernelAccess device;
    device.bound_vec4_ns = 2.0;  // 1 ns per access
    device.fma_gflops = 1.0;     // 1 ns per flop
    device.dispatch_us = 10.0;
    const PipelineCost p{1e6, 2e6, 3};
    EXPECT_NEAR(floor_ms(p, device), 1.0 + 2.0 + 0.03, 1e-12);
    // An empty cycle's cost holds the first dispatch's.
    EXPECT_NEAR(floor_ms(p, device, 0.5), 0.5 + 1.0 + 2.0 + 0.02, 1e-12);
    // Accesses are priced at the cheaper path: addressed vec4s here.
    device.address_vec4_ns = 1.0;
    EXPECT_NEAR(floor_ms(p, device), 0.5 + 2.0 + 0.03, 1e-12);
}

}  // namespace
}  // namespace vkfuse::bench

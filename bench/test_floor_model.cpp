// The floor model's counts against the hand-derived access counts of the
// ideal pipelines (floor_model.cpp) and its pricing against the probe.
#include <gtest/gtest.h>

#include "floor_model.hpp"

namespace vkfuse::bench {
namespace {

Cell cell(Method m, int levels, int sensors, int frames = 3) {
    Cell c;
    c.method.method = m;
    c.method.wavelet = Wavelet::Bior44;
    c.levels = levels;
    c.size = {320, 240};
    c.frames = frames;
    c.sensors = sensors;
    return c;
}

TEST(FloorModel, AccessesPerInputSampleOfTheIdealPipelines) {
    const double in = 320.0 * 240 * 3 * 3;  // QVGA, RGB, K = 3
    // Pointwise: frames once, planes + image + (planes, background) = 4 per fused sample.
    EXPECT_NEAR(ideal_pipeline(cell(Method::Brovey, 0, 1), false).accesses / in, 1 + 4.0 / 3, 1e-9);
    // Laplacian L4, in units of N = H W C (the input is 3 N): level 0 reads
    // the frames, writes G1 and the fused level (3 + 0.75 + 1); levels 1..3
    // 4.75 N / 4^l; the top 4 N / 256; the collapse 2.25 N (1 + 1/4 + 1/16 +
    // 1/64); the metrics 3 N. 12.3125 N in all.
    EXPECT_NEAR(ideal_pipeline(cell(Method::Laplacian, 4, 1), false).accesses / in, 12.3125 / 3, 1e-9);
    // Wavelet L3: level 0 rows 6 N, columns + fusion 4.75 N, inverse 4 N;
    // level 1 a quarter of that (14.75 / 4); level 2 rows 6/16, columns 4/16
    // (no approximation kept), inverse 4/16; metrics 3 N. 22.3125 N in all.
    EXPECT_NEAR(ideal_pipeline(cell(Method::Wavelet, 3, 1), false).accesses / in, 22.3125 / 3, 1e-9);
    // 8-bit frames: a word holds four samples.
    EXPECT_NEAR(ideal_pipeline(cell(Method::Wavelet, 3, 1), false).accesses -
                    ideal_pipeline(cell(Method::Wavelet, 3, 1), true).accesses,
                0.75 * in, 1e-6 * in);
}

TEST(FloorModel, WorkGrowsWithSensorsAndDispatchesDoNot) {
    for (Method m : {Method::ChannelSum, Method::Laplacian, Method::Wavelet}) {
        const int L = m == Method::ChannelSum ? 0 : 3;
        const PipelineCost one = ideal_pipeline(cell(m, L, 1), false), many = ideal_pipeline(cell(m, L, 64), false);
        EXPECT_NEAR(many.accesses, 64 * one.accesses, 1e-9 * many.accesses);
        EXPECT_NEAR(many.flops, 64 * one.flops, 1e-9 * many.flops);
        EXPECT_EQ(many.dispatches, one.dispatches);
    }
}

TEST(FloorModel, PricedAtTheProbedCosts) {
    vk::KernelAccess device;
    device.bound_vec4_ns = 2.0;  // 1 ns per access
    device.fma_gflops = 1.0;     // 1 ns per flop
    device.dispatch_us = 10.0;
    const PipelineCost p{1e6, 2e6, 3};
    EXPECT_NEAR(floor_ms(p, device), 1.0 + 2.0 + 0.03, 1e-12);
}

}  // namespace
}  // namespace vkfuse::bench

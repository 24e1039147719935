// The tile-sparse wavelet planner against full fusion: its CPU twin, fed NaN
// everywhere the plan says nothing is read, must give full fusion's output
// inside the planned rectangle.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fusion_methods.hpp"
#include "core/sparse_wavelet.hpp"
#include "test_support.hpp"

namespace vkfuse::test {
namespace {

using core::CircularRange;
using core::RangeRect;

std::vector<char> marks(int n, std::initializer_list<int> at) {
    std::vector<char> m(std::size_t(n), 0);
    for (int i : at) m[std::size_t(i)] = 1;
    return m;
}

TEST(SparseWavelet, CoverIsTheComplementOfTheLongestGap) {
    const auto expect = [](const CircularRange& r, int start, int length) {
        EXPECT_EQ(r.start, start);
        EXPECT_EQ(r.length, length);
    };
    expect(core::cover(marks(10, {})), 0, 0);
    expect(core::cover(marks(10, {4})), 4, 1);
    expect(core::cover(marks(10, {2, 3, 4})), 2, 3);
    expect(core::cover(marks(10, {8, 9, 0, 1})), 8, 4);        // wraps past the edge
    expect(core::cover(marks(10, {0, 1, 5, 6})), 5, 7);        // gaps of 3 and 2: 5..1
    expect(core::cover(marks(4, {0, 1, 2, 3})), 0, 4);
    EXPECT_TRUE(CircularRange({10, 8, 4}).contains(1));
    EXPECT_FALSE(CircularRange({10, 8, 4}).contains(2));
}

// frames with NaN outside the plan's input, fused by the twin: inside the
// output rectangle every sample is full fusion's (of the clean frames).
void check_plan(const FusionSpec& spec, int h, int w, RangeRect output, std::uint32_t seed) {
    SCOPED_TRACE(std::to_string(h) + "x" + std::to_string(w) + " rows " + std::to_string(output.rows.start) + "+" +
                 std::to_string(output.rows.length) + " cols " + std::to_string(output.cols.start) + "+" +
                 std::to_string(output.cols.length));
    const core::SparseWaveletPlan plan = core::plan_sparse_wavelet(spec, h, w, output);
    std::vector<core::Plane> clean, poisoned;
    for (int k = 0; k < 3; ++k) {
        const ImageD img = random_image(h, w, 1, seed + std::uint32_t(k));
        core::Plane p(h, w);
        p.data = img.data;
        clean.push_back(p);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (!plan.input.rows.contains(y) || !plan.input.cols.contains(x))
                    p.at(y, x) = std::numeric_limits<double>::quiet_NaN();
        poisoned.push_back(std::move(p));
    }
    const core::Plane full = core::fuse_wavelet(clean, spec);
    const core::Plane sparse = core::fuse_wavelet_sparse(poisoned, spec, plan);
    double worst = 0;
    int inside = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!output.rows.contains(y) || !output.cols.contains(x)) continue;
            ++inside;
            const double d = std::abs(sparse.at(y, x) - full.at(y, x));
            ASSERT_FALSE(std::isnan(d)) << "(" << y << ", " << x << ") read something the plan left out";
            worst = std::max(worst, d);
        }
    EXPECT_EQ(inside, output.rows.length * output.cols.length);
    EXPECT_LE(worst, 1e-12);
}

TEST(SparseWavelet, ThePlannedRegionsGiveFullFusionInsideTheOutput) {
    std::uint32_t seed = 1;
    for (Wavelet wv : {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44})
        for (int levels : {1, 2, 3})
            for (auto [h, w] : {std::pair{96, 128}, {75, 83}}) {
                FusionSpec spec;
                spec.wavelet = wv;
                spec.levels = levels;
                SCOPED_TRACE(std::to_string(int(wv)) + " L" + std::to_string(levels));
                // A tile inside, a corner tile (its reach wraps both ways), a
                // strip across, and a tile cut by the last row.
                check_plan(spec, h, w, {{h, 32, 32}, {w, 32, 32}}, seed++);
                check_plan(spec, h, w, {{h, 0, 32}, {w, w - 19, 19}}, seed++);
                check_plan(spec, h, w, {{h, 40, 7}, {w, 0, w}}, seed++);
                check_plan(spec, h, w, {{h, 64, h - 64}, {w, 3, 1}}, seed++);
            }
}

// The halo is real but bounded: at QVGA, bior4.4, 3 levels, a 64 x 64 contact
// in the middle needs part of the frames and part of the work.
TEST(SparseWavelet, AQvgaContactNeedsLessThanFullFusion) {
    FusionSpec spec;
    const RangeRect contact{{240, 96, 64}, {320, 128, 64}};
    check_plan(spec, 240, 320, contact, 77);
    const core::SparseWaveletPlan plan = core::plan_sparse_wavelet(spec, 240, 320, contact);
    EXPECT_FALSE(plan.input.rows.full());
    EXPECT_FALSE(plan.input.cols.full());
    const double work = plan.work_fraction(3, 3);
    EXPECT_GT(work, 64.0 * 64.0 / (240.0 * 320.0));
    EXPECT_LT(work, 0.6);
    EXPECT_EQ(core::plan_sparse_wavelet(spec, 240, 320, {{240, 0, 240}, {320, 0, 320}}).work_fraction(3, 3), 1.0);
    EXPECT_EQ(core::plan_sparse_wavelet(spec, 240, 320, {{240, 0, 0}, {320, 0, 0}}).work_fraction(3, 3), 0.0);
}

TEST(SparseWavelet, OnlyPeriodizationWaveletsArePlanned) {
    FusionSpec symmetric;
    symmetric.mode = WaveletMode::Symmetric;
    EXPECT_THROW(core::plan_sparse_wavelet(symmetric, 64, 64, {{64, 0, 8}, {64, 0, 8}}), std::invalid_argument);
    FusionSpec laplacian;
    laplacian.method = Method::Laplacian;
    EXPECT_THROW(core::plan_sparse_wavelet(laplacian, 64, 64, {{64, 0, 8}, {64, 0, 8}}), std::invalid_argument);
}

}  // namespace
}  // namespace vkfuse::test

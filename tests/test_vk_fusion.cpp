// The Vulkan path against the CPU reference: every method, rule, wavelet and
// mode, odd and tiny sizes, QVGA and VGA, K in {2, 3, 5}, S in {1, 4}, C in {1, 3}.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/method_table.hpp"
#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

constexpr double kFusedTolerance = 1e-5;  // docs/spec.md: Vulkan vs reference

// max-abs picks one frame's coefficient; where two frames' magnitudes differ by
// less than float32 rounding (~1e-7) and their signs differ, float and double
// may pick different frames and the pixel differs by about twice the
// coefficient. Random frames give a few such near-ties per QVGA image at most,
// so max-abs cases allow 1 sample in 10^4 (and at least 4) beyond tolerance;
// a wrong selection rule would put far more samples out.
bool uses_max_abs(const FusionSpec& s) {
    const bool pyramid = s.method == Method::Laplacian || s.method == Method::Wavelet;
    return pyramid && (s.base_rule == Rule::MaxAbs || s.detail_rule == Rule::MaxAbs);
}

void expect_matches(const Image& gpu, const ImageD& ref, const FusionSpec& spec) {
    ASSERT_TRUE(gpu.height == ref.height && gpu.width == ref.width && gpu.channels == ref.channels);
    std::size_t over = 0;
    double worst = 0;
    for (std::size_t i = 0; i < ref.data.size(); ++i) {
        const double d = std::abs(double(gpu.data[i]) - ref.data[i]);
        worst = std::max(worst, d);
        over += d > kFusedTolerance;
    }
    if (!uses_max_abs(spec)) {
        EXPECT_LE(worst, kFusedTolerance);
        return;
    }
    const std::size_t allowed = std::max<std::size_t>(4, ref.data.size() / 10000);
    EXPECT_LE(over, allowed) << "samples beyond " << kFusedTolerance << " (worst " << worst << ")";
}

struct Case {
    FusionSpec spec;
    int height, width, channels, frames, sensors;
    std::string label;
};

std::string describe(const Case& c) {
    return c.label + " " + std::string(to_string(c.spec.method)) + " " + std::string(to_string(c.spec.wavelet)) + "/" +
           std::string(to_string(c.spec.mode)) + " L=" + std::to_string(c.spec.effective_levels()) + " base=" +
           std::string(to_string(c.spec.base_rule)) + " detail=" + std::string(to_string(c.spec.detail_rule)) + " " +
           std::to_string(c.height) + "x" + std::to_string(c.width) + "x" + std::to_string(c.channels) +
           " K=" + std::to_string(c.frames) + " S=" + std::to_string(c.sensors);
}

// Frames with shared structure but different lighting, like one sensor cycle.
std::vector<ImageD> make_frames(const Case& c, std::uint32_t seed) {
    std::vector<ImageD> frames;
    for (int i = 0; i < c.frames * c.sensors; ++i) {
        auto f = (i % 2) ? random_image(c.height, c.width, c.channels, seed + i)
                         : structured_image(c.height, c.width, c.channels, seed + i);
        frames.push_back(f);
    }
    return frames;
}

void check_case(Context& ctx, const Case& c, std::uint32_t seed) {
    SCOPED_TRACE(describe(c));
    auto frames = make_frames(c, seed);
    PlanConfig cfg;
    cfg.fusion = c.spec;
    cfg.height = c.height;
    cfg.width = c.width;
    cfg.channels = c.channels;
    cfg.frames = c.frames;
    cfg.sensors = c.sensors;
    cfg.metrics = {};
    std::vector<Image> f32;
    for (auto& f : frames) f32.push_back(convert<float>(f));
    Plan plan = run_plan(ctx, cfg, f32);
    for (int s = 0; s < c.sensors; ++s) {
        ImageD expected = fuse_reference(std::span(frames).subspan(std::size_t(s) * c.frames, std::size_t(c.frames)), c.spec);
        SCOPED_TRACE("sensor " + std::to_string(s));
        expect_matches(plan.fused(s), expected, c.spec);
    }
}

const Rule kRules[] = {Rule::MaxAbs, Rule::Mean, Rule::Max, Rule::Min};
const Wavelet kWavelets[] = {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44};
const WaveletMode kModes[] = {WaveletMode::Periodization, WaveletMode::Symmetric};

class VulkanFusion : public VulkanTest {};

TEST_F(VulkanFusion, EveryRulePairLaplacian) {
    for (Rule b : kRules)
        for (Rule d : kRules) {
            FusionSpec s;
            s.method = Method::Laplacian;
            s.base_rule = b;
            s.detail_rule = d;
            check_case(ctx(), {s, 37, 53, 3, 3, 2, "rules"}, 11);
        }
}

TEST_F(VulkanFusion, EveryRulePairEveryWaveletAndMode) {
    for (Wavelet w : kWavelets)
        for (WaveletMode m : kModes)
            for (Rule b : kRules)
                for (Rule d : kRules) {
                    FusionSpec s;
                    s.method = Method::Wavelet;
                    s.wavelet = w;
                    s.mode = m;
                    s.levels = 2;
                    s.base_rule = b;
                    s.detail_rule = d;
                    check_case(ctx(), {s, 45, 38, 3, 2, 1, "rules"}, 21);
                }
}

// Every row of the method table at its defaults and within its limits, against
// its own reference: a method added to the table is swept here before it has
// tests of its own (K 1, 2, 5 and C 1, 3 where the row allows them; odd and
// quad-aligned sizes; sensors batched).
TEST_F(VulkanFusion, EveryMethodRowAgainstItsReference) {
    for (const core::MethodInfo& row : core::method_table()) {
        FusionSpec s;
        s.method = row.method;
        const std::vector<int> frames = row.exact_frames ? std::vector<int>{row.exact_frames} : std::vector<int>{1, 2, 5};
        const std::vector<int> channels =
            row.exact_channels ? std::vector<int>{row.exact_channels} : std::vector<int>{1, 3};
        for (int k : frames)
            for (int c : channels)
                for (auto [h, w] : {std::pair{75, 83}, {96, 128}})  // the default wavelet levels need sides >= 72
                    check_case(ctx(), {s, h, w, c, k, 2, "row " + std::string(row.name)}, 41);
    }
}

TEST_F(VulkanFusion, PointwiseMethods) {
    FusionSpec brovey;
    brovey.method = Method::Brovey;
    FusionSpec channel_sum;
    channel_sum.method = Method::ChannelSum;
    for (auto [h, w] : {std::pair{1, 1}, {2, 3}, {5, 7}, {61, 97}, {240, 320}}) {
        check_case(ctx(), {brovey, h, w, 3, 5, 1, "brovey"}, 31);
        check_case(ctx(), {brovey, h, w, 1, 2, 4, "brovey"}, 32);
        check_case(ctx(), {channel_sum, h, w, 3, 3, 4, "channel-sum"}, 33);
    }
}

TEST_F(VulkanFusion, LaplacianSizesAndLevels) {
    int i = 0;
    // Widths of whole pairs of quads (8, 16, 40, 320, 640) take the plane4
    // kernels, the row's first and last quad in one at 8; 31 (levels 31, 16,
    // 8, 4, 2) alternates them with the scalar ones, so each collapses onto a
    // level the other made.
    for (auto [h, w] : {std::pair{1, 1}, {1, 9}, {9, 1}, {2, 3}, {5, 7}, {3, 8}, {2, 16}, {7, 40}, {5, 31}, {61, 97},
                        {240, 320}, {480, 640}})
        for (int levels : {1, 4, 6}) {
            FusionSpec s;
            s.method = Method::Laplacian;
            s.levels = levels;
            const int K = std::array{2, 3, 5}[i % 3];
            const int S = (i % 2) ? 4 : 1;
            const int C = (i % 4 < 2) ? 3 : 1;
            ++i;
            if (h * w >= 480 * 640 && S > 1) continue;  // keep VGA single-sensor: the CPU oracle is the slow part
            check_case(ctx(), {s, h, w, C, K, S, "sizes"}, 40 + i);
        }
}

TEST_F(VulkanFusion, WaveletSizesLevelsAndModes) {
    int i = 0;
    for (Wavelet wl : kWavelets)
        for (WaveletMode m : kModes)
            for (auto [h, w] : {std::pair{2, 3}, {5, 7}, {16, 16}, {61, 97}, {240, 320}, {480, 640}}) {
                const int max_levels = max_wavelet_levels(wl, h, w);
                for (int levels : {1, 3, max_levels}) {
                    if (levels < 1 || levels > max_levels) continue;
                    FusionSpec s;
                    s.method = Method::Wavelet;
                    s.wavelet = wl;
                    s.mode = m;
                    s.levels = levels;
                    const int K = std::array{2, 3, 5}[i % 3];
                    const int S = (i % 2) ? 4 : 1;
                    const int C = (i % 4 < 2) ? 3 : 1;
                    ++i;
                    if (h * w >= 240 * 320 && (S > 1 || levels != 3)) continue;
                    check_case(ctx(), {s, h, w, C, K, S, "sizes"}, 60 + i);
                }
            }
}

TEST_F(VulkanFusion, IdenticalFramesFuseToThemselves) {
    auto frame = structured_image(33, 47, 3, 5);
    std::vector<Image> frames(3, convert<float>(frame));
    std::vector<FusionSpec> specs;
    FusionSpec s;
    s.method = Method::Brovey;
    specs.push_back(s);
    s.method = Method::Laplacian;
    specs.push_back(s);
    for (Wavelet w : kWavelets)
        for (WaveletMode m : kModes) {
            s.method = Method::Wavelet;
            s.wavelet = w;
            s.mode = m;
            s.levels = 1;
            specs.push_back(s);
        }
    for (auto& spec : specs) {
        SCOPED_TRACE(std::string(to_string(spec.method)) + " " + std::string(to_string(spec.wavelet)));
        PlanConfig cfg{spec, 33, 47, 3, 3, 1};
        cfg.metrics = {};
        Plan plan = run_plan(ctx(), cfg, frames);
        EXPECT_LE(max_abs_diff(plan.fused(0), frame), kFusedTolerance);
    }
}

// Symmetric-mode lifting reconstructs perfectly for any size, so fusing
// identical frames must give the frame back at every size and level count.
TEST_F(VulkanFusion, SymmetricModeRoundTripsAtEverySize) {
    for (Wavelet wl : kWavelets)
        for (int h = 1; h <= 23; h += 2)
            for (int w : {h, h + 1, 2 * h + 3}) {
                const int max_levels = max_wavelet_levels(wl, h, w);
                for (int levels = 1; levels <= max_levels; ++levels) {
                    FusionSpec s;
                    s.method = Method::Wavelet;
                    s.wavelet = wl;
                    s.mode = WaveletMode::Symmetric;
                    s.levels = levels;
                    SCOPED_TRACE(std::string(to_string(wl)) + " " + std::to_string(h) + "x" + std::to_string(w) +
                                 " L=" + std::to_string(levels));
                    auto frame = random_image(h, w, 1, std::uint32_t(h * 100 + w));
                    std::vector<Image> frames(2, convert<float>(frame));
                    PlanConfig cfg{s, h, w, 1, 2, 1};
                    cfg.metrics = {};
                    Plan plan = run_plan(ctx(), cfg, frames);
                    EXPECT_LE(max_abs_diff(plan.fused(0), frame), kFusedTolerance);
                }
            }
}

TEST_F(VulkanFusion, RunsAreBitIdentical) {
    FusionSpec s;  // default: wavelet bior4.4, 3 levels
    PlanConfig cfg{s, 120, 160, 3, 3, 2};
    cfg.metrics = {Metric::Sharpness, Metric::Contrast};
    std::vector<Image> frames;
    for (int i = 0; i < 6; ++i) frames.push_back(convert<float>(structured_image(120, 160, 3, 90 + i)));
    std::vector<FrameView> views;
    for (auto& f : frames) views.push_back(FrameView::of(f));
    Plan plan(ctx(), cfg);
    plan.run(views);
    Image first = plan.fused(1);
    Metrics m1 = plan.metrics(1);
    for (int r = 0; r < 3; ++r) {
        plan.run(views);
        ASSERT_EQ(0, std::memcmp(first.data.data(), plan.fused(1).data.data(), first.size() * sizeof(float)));
        EXPECT_EQ(m1.sharpness, plan.metrics(1).sharpness);
        EXPECT_EQ(m1.contrast, plan.metrics(1).contrast);
    }
}

// Every kernel that reads the frames as uploaded (unpack, and the first
// passes that read them themselves: rows of whole quads, 64 x 48) in 8-bit.
TEST_F(VulkanFusion, EightBitFramesUnpackLikeFiles) {
    std::vector<FusionSpec> specs(3);
    specs[0].method = Method::Laplacian;
    for (int i : {1, 2}) {
        specs[std::size_t(i)].method = Method::Wavelet;
        specs[std::size_t(i)].wavelet = Wavelet::Bior44;
        specs[std::size_t(i)].mode = i == 1 ? WaveletMode::Periodization : WaveletMode::Symmetric;
    }
    for (FusionSpec s : specs)
        for (auto [h, w] : {std::pair{31, 29}, {48, 64}})
            for (int c : {1, 3}) {
                SCOPED_TRACE(std::string(to_string(s.method)) + " " + std::to_string(w) + "x" + std::to_string(h) +
                             "x" + std::to_string(c));
                std::vector<std::vector<std::uint8_t>> raw(2, std::vector<std::uint8_t>(std::size_t(h) * w * c));
                std::vector<ImageD> ref(2, ImageD(h, w, c));
                for (int k = 0; k < 2; ++k)
                    for (std::size_t i = 0; i < raw[std::size_t(k)].size(); ++i) {
                        raw[std::size_t(k)][i] = std::uint8_t((i * 37 + std::size_t(k) * 101) % 256);
                        ref[std::size_t(k)].data[i] = raw[std::size_t(k)][i] / 255.0;
                    }
                s.detail_rule = Rule::Mean;  // 8-bit frames tie in max-abs all the time
                if (s.method == Method::Wavelet) s.levels = max_wavelet_levels(s.wavelet, h, w);
                PlanConfig cfg{s, h, w, c, 2, 1};
                cfg.input = PixelType::U8;
                cfg.metrics = {};
                Plan plan(ctx(), cfg);
                std::vector<FrameView> views;
                for (auto& r : raw) views.push_back({r.data(), h, w, c, PixelType::U8});
                plan.run(views);
                EXPECT_LE(max_abs_diff(plan.fused(0), fuse_reference(ref, s)), kFusedTolerance);
            }
}

TEST_F(VulkanFusion, RejectsFramesOfTheWrongShape) {
    FusionSpec s;
    s.method = Method::Brovey;
    PlanConfig cfg{s, 8, 8, 3, 2, 1};
    Plan plan(ctx(), cfg);
    Image a(8, 8, 3), b(8, 9, 3);
    std::vector<FrameView> views{FrameView::of(a), FrameView::of(b)};
    EXPECT_THROW(plan.run(views), Error);
    std::vector<FrameView> one{FrameView::of(a)};
    EXPECT_THROW(plan.run(one), Error);
}

}  // namespace
}  // namespace vkfuse::test

// vk::CachedFusion (the study's multi-scale path): fusing combinations from
// coefficients decomposed once gives, for every source, the metrics a plan
// gives when it fuses the same frames and takes the same fusion of the
// background frames as its background; bad combinations get one line each.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <vector>

#include "expect_error.hpp"
#include "test_support.hpp"
#include "study/cached_fusion.hpp"
#include "vk_fixture.hpp"

namespace vkfuse::test {
namespace {

constexpr int kFrames = 5;
// Room for one source's planes of kFrames 48 x 64 frames (at most 49 x 65
// samples each, 3 channels), not two.
constexpr std::uint64_t kOneSourceBytes = std::uint64_t(kFrames) * 3 * 49 * 65 * 4;
constexpr std::uint64_t kNoSourceFits = 1;

struct Sources {
    int height, width;
    std::vector<Image> background;                   // float32, one per frame
    std::vector<std::vector<std::uint8_t>> objects;  // 8-bit, object-major
    int object_count;

    Sources(int h, int w, int objects_n) : height(h), width(w), object_count(objects_n) {
        for (int f = 0; f < kFrames; ++f) background.push_back(convert<float>(random_image(h, w, 3, 100u + f)));
        for (int o = 0; o < objects_n; ++o)
            for (int f = 0; f < kFrames; ++f) {
                const ImageD img = random_image(h, w, 3, 200u + 17u * o + f);
                std::vector<std::uint8_t> bytes(img.size());
                for (std::size_t i = 0; i < img.size(); ++i) bytes[i] = std::uint8_t(std::lround(img.data[i] * 255));
                objects.push_back(std::move(bytes));
            }
    }
    FrameView object(int o, std::size_t f) const {
        return {objects[std::size_t(o) * kFrames + f].data(), height, width, 3, PixelType::U8};
    }
    std::vector<FrameView> all() const {
        std::vector<FrameView> v;
        for (const Image& b : background) v.push_back(FrameView::of(b));
        for (int o = 0; o < object_count; ++o)
            for (std::size_t f = 0; f < kFrames; ++f) v.push_back(object(o, f));
        return v;
    }
};

// What a plan gives for one combination: the backgrounds fused and read
// back, then the objects fused with that image as their background.
std::vector<Metrics> with_plans(Context& ctx, const FusionSpec& spec, const Sources& s,
                                const std::vector<std::size_t>& combination) {
    PlanConfig bg;
    bg.fusion = spec;
    bg.height = s.height;
    bg.width = s.width;
    bg.frames = int(combination.size());
    bg.metrics = {};
    Plan backgrounds(ctx, bg);
    std::vector<FrameView> frames;
    for (std::size_t f : combination) frames.push_back(FrameView::of(s.background[f]));
    backgrounds.run(frames);
    const Image fused_background = backgrounds.fused(0);
    PlanConfig cfg = bg;
    cfg.sensors = s.object_count;
    cfg.input = PixelType::U8;
    cfg.want_fused = false;
    cfg.metrics = MetricSet::all();
    Plan objects(ctx, cfg);
    frames.clear();
    for (int o = 0; o < s.object_count; ++o) {
        objects.set_background(o, FrameView::of(fused_background));
        for (std::size_t f : combination) frames.push_back(s.object(o, f));
    }
    objects.run(frames);
    std::vector<Metrics> out;
    for (int o = 0; o < s.object_count; ++o) out.push_back(objects.metrics(o));
    return out;
}

std::vector<std::vector<std::size_t>> subsets(std::size_t k) {
    std::vector<std::vector<std::size_t>> out;
    for (unsigned mask = 0; mask < (1u << kFrames); ++mask) {
        if (std::size_t(__builtin_popcount(mask)) != k) continue;
        std::vector<std::size_t> c;
        for (std::size_t f = 0; f < kFrames; ++f)
            if (mask & (1u << f)) c.push_back(f);
        out.push_back(c);
    }
    return out;
}

void expect_close(double expected, double got, const std::string& what) {
    EXPECT_LE(std::abs(got - expected), 1e-5 * std::abs(expected) + 1e-12) << what << ": plan " << expected
                                                                            << ", cached " << got;
}

struct Case {
    Method method;
    Wavelet wavelet;
    WaveletMode mode;
    int height, width;
    // Limits each group of sources' buffers: small enough for one source per
    // group, so that every source's coefficients sit in a group of their own
    // (0: the device's, one group; kNoSourceFits: one group of every source,
    // reached through device addresses).
    std::uint64_t max_binding_bytes = 0;
    bool addressed = false;  // in a context whose kernels all use device addresses
};

class CachedFusionTest : public VulkanTest, public ::testing::WithParamInterface<Case> {};

// e.g. wavelet_bior44_periodization_48x64_one_source_groups_addressed
std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    const Case& c = info.param;
    std::string name(to_string(c.method));
    if (c.method == Method::Wavelet) name += "_" + std::string(to_string(c.wavelet)) + "_" + std::string(to_string(c.mode));
    name += "_" + std::to_string(c.height) + "x" + std::to_string(c.width);
    if (c.max_binding_bytes == kOneSourceBytes) name += "_small_groups";
    if (c.max_binding_bytes == kNoSourceFits) name += "_one_addressed_group";
    if (c.addressed) name += "_addressed";
    std::string out;
    for (char ch : name)
        if (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_') out += ch;
    return out;
}

// Every 2- and 3-subset of five frames (ten each: a full batch and a short
// one for three sources), as the plans give them.
TEST_P(CachedFusionTest, MatchesPlansForEveryCombination) {
    const Case c = GetParam();
    if (c.addressed || c.max_binding_bytes == kNoSourceFits) SKIP_WITHOUT_DEVICE_ADDRESSES();
    FusionSpec spec;
    spec.method = c.method;
    spec.wavelet = c.wavelet;
    spec.mode = c.mode;
    spec.levels = 2;
    // On a GPU the cached path's kernels and the plans' may contract
    // multiply-adds differently (kModuleUlps). Where two 8-bit frames'
    // coefficients tie in magnitude with opposite signs, which these frames
    // make common, max-abs then lets rounding pick either frame (docs/spec.md,
    // near-ties), and one flip moves a metric by far more than 1e-5. There the
    // detail rule is max, which a rounding difference moves by no more than
    // itself; on a CPU device the two paths give equal bits under max-abs.
    if (module_ulps(ctx()) > 0) spec.detail_rule = Rule::Max;
    const Sources s(c.height, c.width, 2);
    vk::CachedFusion cached(c.addressed ? addressed_context() : ctx(),
                            {spec, c.height, c.width, 3, 1 + s.object_count, kFrames, c.max_binding_bytes}, s.all());
    for (std::size_t k : {2u, 3u}) {
        const auto combinations = subsets(k);
        const auto got = cached.score(combinations);
        ASSERT_EQ(got.size(), combinations.size());
        for (std::size_t i = 0; i < combinations.size(); ++i) {
            const std::vector<Metrics> expected = with_plans(ctx(), spec, s, combinations[i]);
            ASSERT_EQ(got[i].size(), expected.size());
            for (std::size_t o = 0; o < expected.size(); ++o) {
                const std::string what = "k " + std::to_string(k) + " combination " + std::to_string(i) + " object " +
                                         std::to_string(o);
                expect_close(expected[o].sharpness, got[i][o].sharpness, what + " sharpness");
                expect_close(expected[o].contrast, got[i][o].contrast, what + " contrast");
                expect_close(*expected[o].background_diff, *got[i][o].background_diff, what + " background_diff");
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, CachedFusionTest,
                         ::testing::Values(Case{Method::Wavelet, Wavelet::Haar, WaveletMode::Periodization, 48, 64},
                                           Case{Method::Wavelet, Wavelet::Bior44, WaveletMode::Periodization, 48, 64},
                                           Case{Method::Wavelet, Wavelet::Db2, WaveletMode::Periodization, 29, 37},
                                           Case{Method::Wavelet, Wavelet::Bior22, WaveletMode::Symmetric, 30, 44},
                                           Case{Method::Laplacian, Wavelet::Haar, WaveletMode::Periodization, 48, 64},
                                           Case{Method::Laplacian, Wavelet::Haar, WaveletMode::Periodization, 29, 37},
                                           Case{Method::Wavelet, Wavelet::Bior44, WaveletMode::Periodization, 48, 64,
                                                kOneSourceBytes},
                                           Case{Method::Wavelet, Wavelet::Bior22, WaveletMode::Symmetric, 30, 44,
                                                kOneSourceBytes},
                                           Case{Method::Laplacian, Wavelet::Haar, WaveletMode::Periodization, 48, 64,
                                                kOneSourceBytes},
                                           Case{Method::Laplacian, Wavelet::Haar, WaveletMode::Periodization, 29, 37,
                                                kOneSourceBytes},
                                           Case{Method::Wavelet, Wavelet::Bior44, WaveletMode::Periodization, 48, 64,
                                                kNoSourceFits},
                                           Case{Method::Laplacian, Wavelet::Haar, WaveletMode::Periodization, 48, 64,
                                                kNoSourceFits},
                                           Case{Method::Wavelet, Wavelet::Bior22, WaveletMode::Symmetric, 30, 44,
                                                kOneSourceBytes, true},
                                           Case{Method::Laplacian, Wavelet::Haar, WaveletMode::Periodization, 29, 37,
                                                kOneSourceBytes, true}),
                         case_name);

TEST_F(CachedFusionTest, RefusesWhatItCannotFuse) {
    FusionSpec spec;
    spec.method = Method::Wavelet;
    spec.levels = 1;
    const Sources s(32, 32, 1);
    vk::CachedFusion cached(ctx(), {spec, 32, 32, 3, 2, kFrames}, s.all());
    const std::vector<std::vector<std::size_t>> twice{{1, 1}}, past{{0, 5}}, mixed{{0, 1}, {0, 1, 2}};
    const std::string subject = "cached fusion";
    expect_error([&] { cached.score(twice); }, subject, ErrorKind::InvalidArgument, "names a frame twice");
    expect_error([&] { cached.score(past); }, subject, ErrorKind::InvalidArgument, "past 5");
    expect_error([&] { cached.score(mixed); }, subject, ErrorKind::InvalidArgument, "of one size");
    FusionSpec brovey;
    brovey.method = Method::Brovey;
    expect_error([&] { vk::CachedFusion(ctx(), {brovey, 32, 32, 3, 2, kFrames}, s.all()); }, subject,
                 ErrorKind::InvalidArgument, "brovey has no coefficients to fuse from");
    expect_error([&] { vk::CachedFusion(ctx(), {spec, 32, 32, 3, 3, kFrames}, s.all()); }, subject,
                 ErrorKind::InvalidArgument, "images for");
}

}  // namespace
}  // namespace vkfuse::test

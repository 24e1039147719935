// SkipPolicy::Tiles: a changed sensor fuses only what its changed tiles need.
// Inside the rectangle it fused, its result has full fusion's bits; outside,
// its fused reference's; a large change is fused whole, an idle sensor not at
// all, and nothing a sparse cycle leaves behind reaches the next one.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "skip_scene.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

class VulkanSkipTiles : public VulkanTest {};

Image fused_reference(const Scene& s, const FusionSpec& spec) {
    std::vector<ImageD> means;
    for (const Image& m : s.reference.mean) means.push_back(convert<double>(m));
    return convert<float>(fuse_reference(means, spec));
}

// Samples of `got` that differ from full fusion inside the region, and from
// the fused reference outside it.
int wrong_samples(const Image& got, const Image& full, const Image& background, const SkipRegion& region) {
    int wrong = 0;
    for (int y = 0; y < got.height; ++y)
        for (int x = 0; x < got.width; ++x)
            for (int c = 0; c < got.channels; ++c) {
                const Image& want = region.contains(y, x, got.height, got.width) ? full : background;
                wrong += got.at(y, x, c) != want.at(y, x, c);
            }
    return wrong;
}

void check_tiles(Context& ctx, const Scene& scene, const FusionSpec& spec) {
    const int H = scene.h, W = scene.w;
    const Image background = fused_reference(scene, spec);
    Plan tiles(ctx, skip_config(scene, 4, spec, SkipPolicy::Tiles, 8.0));
    Plan full(ctx, skip_config(scene, 4, spec, SkipPolicy::Off, 8.0));
    for (int s = 0; s < 4; ++s) {
        tiles.set_skip_reference(s, scene.reference);
        tiles.set_background(s, FrameView::of(scene.reference.mean[0]));
        full.set_background(s, FrameView::of(scene.reference.mean[0]));
    }
    // Two cycles: sensor 0 pressed inside, then elsewhere; sensor 1 idle,
    // then pressed; sensor 2 pressed across a corner (its reach wraps both
    // ways: its rectangle does too), then idle; sensor 3 pressed over most of the frame (fused whole).
    const std::vector<std::vector<std::vector<Press>>> cycles = {
        {{{H / 2, H / 2 + 12, W / 2 - 20, W / 2 - 4}}, {}, {{0, 10, W - 9, W}, {H - 6, H, 0, 5}}, {{0, H, 8, W - 8}}},
        {{{40, 50, 40, 60}}, {{H - 20, H - 5, 5, 30}}, {}, {{0, H, 0, W}}},
    };
    for (std::size_t c = 0; c < cycles.size(); ++c) {
        std::vector<std::vector<Bytes>> frames;
        for (int s = 0; s < 4; ++s) frames.push_back(frames_of(scene, std::uint32_t(100 * c + s), 3.0, cycles[c][std::size_t(s)]));
        const std::vector<FrameView> all = views(scene, frames);
        tiles.run(all);
        full.run(all);
        for (int s = 0; s < 4; ++s) {
            SCOPED_TRACE("cycle " + std::to_string(c) + " sensor " + std::to_string(s));
            const SkipOutcome o = tiles.skip_outcome(s);
            const bool pressed = !cycles[c][std::size_t(s)].empty();
            EXPECT_EQ(o.idle, !pressed);
            if (!pressed) {
                EXPECT_EQ(o.fused_fraction, 0.0);
                EXPECT_EQ(wrong_samples(tiles.fused(s), full.fused(s), background, o.fused_region), 0);
                continue;
            }
            const bool whole = s == 3;
            EXPECT_EQ(o.fused_fraction == 1.0, whole) << o.fused_fraction;
            EXPECT_GT(o.fused_fraction, 0.0);
            EXPECT_EQ(wrong_samples(tiles.fused(s), full.fused(s), background, o.fused_region), 0);
            // The metrics are those of the result as it is.
            const Metrics got = tiles.metrics(s);
            const Metrics want = metrics_reference(convert<double>(tiles.fused(s)), nullptr);
            EXPECT_NEAR(got.sharpness, want.sharpness, 1e-5 * want.sharpness);
            EXPECT_NEAR(got.contrast, want.contrast, 1e-5 * want.contrast);
        }
    }
}

TEST_F(VulkanSkipTiles, ChangedTilesHaveFullFusionsBitsAndTheRestTheReferences) {
    for (Wavelet w : {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44}) {
        FusionSpec spec;
        spec.wavelet = w;
        spec.levels = 2;
        SCOPED_TRACE(std::string(to_string(w)));
        check_tiles(ctx(), make_scene(192, 256, 3, 3, 5), spec);
    }
}

// The kernels' device-address variants (plans beyond maxStorageBufferRange)
// read the same records.
TEST_F(VulkanSkipTiles, DeviceAddressesToo) {
    SKIP_WITHOUT_DEVICE_ADDRESSES();
    FusionSpec bior44;
    bior44.levels = 2;
    check_tiles(addressed_context(), make_scene(192, 256, 3, 2, 17), bior44);
}

// Rows that are not whole quads or whose halves are not multiples of 8 take
// the general kernels; odd sizes are padded as pywt pads them.
TEST_F(VulkanSkipTiles, OddSizesAndTheDefaultWavelet) {
    check_tiles(ctx(), make_scene(191, 250, 3, 2, 9), FusionSpec{});
    FusionSpec haar3;
    haar3.wavelet = Wavelet::Haar;
    haar3.levels = 3;
    check_tiles(ctx(), make_scene(240, 320, 3, 3, 13), haar3);
}

// Where the plan cannot fuse sparsely (symmetric mode, the Laplacian, fp16),
// Tiles fuses a changed sensor whole, as Static.
TEST_F(VulkanSkipTiles, OtherFusionsFuseChangedSensorsWhole) {
    const Scene scene = make_scene(96, 128, 3, 2, 21);
    FusionSpec symmetric;
    symmetric.mode = WaveletMode::Symmetric;
    symmetric.levels = 2;
    FusionSpec laplacian;
    laplacian.method = Method::Laplacian;
    for (const FusionSpec& spec : {symmetric, laplacian}) {
        Plan tiles(ctx(), skip_config(scene, 1, spec, SkipPolicy::Tiles, 8.0));
        tiles.set_skip_reference(0, scene.reference);
        tiles.set_background(0, FrameView::of(scene.reference.mean[0]));
        const std::vector<std::vector<Bytes>> frames = {frames_of(scene, 3, 3.0, std::vector<Press>{{10, 20, 10, 20}})};
        tiles.run(views(scene, frames));
        EXPECT_EQ(tiles.skip_outcome(0).fused_fraction, 1.0);
    }
}

}  // namespace
}  // namespace vkfuse::test

// Every method fact on its row: each consumer that once switched on a Method
// now asks the method's rows (core/method_table.hpp, vk/plan/method_recorders.hpp),
// so walking every row shows what a new method gets: the study's cache
// either fuses it or refuses it naming it, tile-sparse planning likewise,
// and the two rows agree on what the method is.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "core/method_table.hpp"
#include "core/sparse_wavelet.hpp"
#include "vkfuse/core/error.hpp"
#include "test_support.hpp"
#include "study/cached_fusion.hpp"
#include "vk/plan/method_recorders.hpp"
#include "vk_fixture.hpp"

namespace vkfuse::test {
namespace {

class MethodRows : public VulkanTest {};

FusionSpec spec_of(Method m, WaveletMode mode = WaveletMode::Periodization) {
    FusionSpec s;
    s.method = m;
    s.mode = mode;
    s.levels = 1;
    return s;
}

TEST_F(MethodRows, TheStudysCacheFusesOrRefusesEveryMethodByName) {
    constexpr int kH = 32, kW = 48, kSources = 2, kFrames = 3;
    std::vector<Image> frames;
    for (int i = 0; i < kSources * kFrames; ++i) frames.push_back(convert<float>(random_image(kH, kW, 3, 300u + i)));
    std::vector<FrameView> views;
    for (const Image& f : frames) views.push_back(FrameView::of(f));
    int cached = 0;
    for (const core::MethodInfo& row : core::method_table()) {
        const std::string name(row.name);
        SCOPED_TRACE(name);
        const vk::MethodRecorder& vk_row = vk::method_recorder(row.method);
        EXPECT_EQ(vk_row.method, row.method);
        // A method the cache holds has both halves of it, and only a
        // multi-scale one has coefficients to hold.
        EXPECT_EQ(vk_row.decompose != nullptr, vk_row.fuse_cached != nullptr);
        EXPECT_EQ(vk::CachedFusion::supports(row.method), vk_row.caches_coefficients());
        if (vk_row.caches_coefficients()) {
            EXPECT_EQ(vk_row.shape, vk::GraphShape::Multiscale);
        }
        const vk::CachedFusionShape shape{spec_of(row.method), kH, kW, 3, kSources, kFrames};
        if (!vk::CachedFusion::supports(row.method)) {
            try {
                vk::CachedFusion refused(ctx(), shape, views);
                ADD_FAILURE() << "a cache of " << name << " was built";
            } catch (const Error& e) {
                EXPECT_EQ(e.kind(), ErrorKind::InvalidArgument);
                EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
            }
            continue;
        }
        vk::CachedFusion cache(ctx(), shape, views);
        const std::vector<std::vector<std::size_t>> combinations{{0, 1}, {1, 2}, {0, 1, 2}};
        const auto scores = cache.score(std::span(combinations).first(2));
        ASSERT_EQ(scores.size(), 2u);
        ASSERT_EQ(scores[0].size(), std::size_t(kSources - 1));  // every source but the background
        EXPECT_GT(scores[0][0].contrast, 0.0);
        ++cached;
    }
    EXPECT_GE(cached, 2);  // the wavelet and the Laplacian methods
}

TEST(MethodRowsCpu, TileSparsePlanningAsksTheRow) {
    int sparse = 0;
    for (const core::MethodInfo& row : core::method_table())
        for (WaveletMode mode : {WaveletMode::Periodization, WaveletMode::Symmetric}) {
            const FusionSpec spec = spec_of(row.method, mode);
            const std::string what = std::string(row.name) + " " + std::string(to_string(mode));
            const core::RangeRect rect{{64, 8, 16}, {64, 8, 16}};
            if (core::fuses_tile_sparse(spec)) {
                EXPECT_NO_THROW(core::plan_sparse_wavelet(spec, 64, 64, rect)) << what;
                ++sparse;
            } else {
                try {
                    core::plan_sparse_wavelet(spec, 64, 64, rect);
                    ADD_FAILURE() << what << " was planned tile-sparsely";
                } catch (const std::invalid_argument& e) {
                    EXPECT_NE(std::string(e.what()).find(row.name), std::string::npos) << e.what();
                }
            }
        }
    EXPECT_EQ(sparse, 1);  // periodization wavelets
}

}  // namespace
}  // namespace vkfuse::test

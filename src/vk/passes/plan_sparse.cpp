// Tile-sparse fusion's region records (vk/passes/plan_sparse.hpp).
#include "vk/passes/plan_sparse.hpp"

#include <algorithm>
#include <cstring>

#include "core/method_table.hpp"
#include "vk/engine/kernel_codes.hpp"
#include "vk/engine/recorder.hpp"
#include "vkfuse/core/skip.hpp"

namespace vkfuse::vk {
namespace {

constexpr std::uint32_t kRecord = 8;  // uints per record (shaders/sparse.glsl)

int mod(int a, int m) { return ((a % m) + m) % m; }

// The blocks of `block` outputs holding any output of the range.
core::CircularRange blocks_of(const core::CircularRange& outputs, int block) {
    std::vector<char> marks(std::size_t((outputs.n + block - 1) / block), 0);
    for (int i = 0; i < outputs.length; ++i) marks[std::size_t(mod(outputs.start + i, outputs.n) / block)] = 1;
    return core::cover(marks);
}

// The coefficients o (of `pairs`) whose synthesis gives the output samples
// of the range: sample m comes from o = ((m - shift) mod 2 pairs) / 2.
core::CircularRange coefficients_of(const core::CircularRange& samples, int pairs, int shift) {
    std::vector<char> marks(std::size_t(pairs), 0);
    for (int i = 0; i < samples.length; ++i) marks[std::size_t(mod(mod(samples.start + i, samples.n) - shift, 2 * pairs) / 2)] = 1;
    return core::cover(marks);
}

core::CircularRange whole(int n) { return {n, 0, n}; }

}  // namespace

bool sparse_capable(const PlanConfig& cfg) {
    return cfg.skip.policy == SkipPolicy::Tiles && cfg.fuse && core::fuses_tile_sparse(cfg.fusion) &&
           cfg.precision == Precision::Fp32;
}

SparseRegions::SparseRegions(Context::Impl& ctx, const PlanConfig& cfg) : cfg_(cfg) {
    whole_.rect = {whole(cfg.height), whole(cfg.width)};
    whole_.plan = core::plan_sparse_wavelet(cfg.fusion, cfg.height, cfg.width, whole_.rect);
    const std::size_t uses = 4 * whole_.plan.levels.size() + 1;  // four passes a level, and the compose
    regions_ = Buffer(ctx, uses * std::size_t(cfg.sensors) * kRecord * 4, MemoryUse::Upload);
    backgrounds_ = Buffer(ctx, std::size_t(cfg.sensors) * std::size_t(cfg.channels) * std::size_t(cfg.height) *
                                   std::size_t(cfg.width) * 4,
                          MemoryUse::Upload);
    std::memset(regions_.mapped(), 0, uses * std::size_t(cfg.sensors) * kRecord * 4);
}

std::uint32_t SparseRegions::declare(const SparseUse& use) {
    uses_.push_back(use);
    extent_.push_back({0, 0});
    return 1 + std::uint32_t(uses_.size() - 1) * std::uint32_t(cfg_.sensors) * kRecord;
}

void SparseRegions::set_background(int sensor, const Image& fused) {
    const std::size_t pixels = std::size_t(cfg_.height) * std::size_t(cfg_.width), C = std::size_t(cfg_.channels);
    float* out = static_cast<float*>(backgrounds_.mapped()) + std::size_t(sensor) * C * pixels;
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < C; ++c) out[c * pixels + p] = fused.data[p * C + c];
}

void SparseRegions::begin_run() {
    for (auto& e : extent_) e = {0, 0};
}

void SparseRegions::shrink(VkDispatchIndirectCommand* args) const {
    for (std::size_t u = 0; u < uses_.size(); ++u) {
        const SparseUse& use = uses_[u];
        if (use.pass == SparsePass::Compose) continue;
        const std::uint32_t lines = extent_[u][0], blocks = extent_[u][1];
        const Grid grid = grid_1d(std::uint64_t(lines) * blocks, VKFUSE_LINE_GROUP);
        args[use.dispatch].x = grid.x;
        args[use.dispatch].y = grid.y;
    }
}

void SparseRegions::write_record(int use, int slot, const std::uint32_t (&record)[8]) {
    const std::uint32_t lines = record[4] ? 2 * record[1] : record[1];
    extent_[std::size_t(use)] = {std::max(extent_[std::size_t(use)][0], lines),
                                 std::max(extent_[std::size_t(use)][1], record[3])};
    auto* at = static_cast<std::uint32_t*>(regions_.mapped()) +
               (std::size_t(use) * std::size_t(cfg_.sensors) + std::size_t(slot)) * kRecord;
    std::memcpy(at, record, sizeof record);
}

void SparseRegions::write(int slot, int sensor, const std::optional<core::SparseChoice>& choice) {
    // Fused whole: the records of a plan of the whole frame.
    const core::SparseChoice& chosen = choice ? *choice : whole_;
    const core::SparseWaveletPlan& plan = chosen.plan;
    const int shift = (plan.filter_length / 2) % 2 == 0 ? 1 : 0;
    const auto u32 = [](int v) { return std::uint32_t(v); };
    for (std::size_t u = 0; u < uses_.size(); ++u) {
        const SparseUse& use = uses_[u];
        const core::SparseWaveletLevel& lv = plan.levels[std::size_t(use.level)];
        core::CircularRange lines, blocks;
        int half = 0;
        switch (use.pass) {
            case SparsePass::ForwardRows:
                lines = lv.forward_rows.rows;
                blocks = blocks_of(lv.forward_rows.cols, use.block);
                break;
            case SparsePass::ForwardCols:
                lines = lv.forward_cols.cols;
                half = lv.pair_cols;
                blocks = blocks_of(lv.forward_cols.rows, use.block);
                break;
            case SparsePass::InverseCols:
                lines = lv.inverse_cols.cols;
                half = lv.pair_cols;
                blocks = blocks_of(coefficients_of(lv.inverse_cols.rows, lv.pair_rows, shift), use.block);
                break;
            case SparsePass::InverseRows:
                lines = lv.inverse_rows.rows;
                blocks = blocks_of(coefficients_of(lv.inverse_rows.cols, lv.pair_cols, shift), use.block);
                break;
            case SparsePass::Compose:
                lines = chosen.rect.rows;
                blocks = chosen.rect.cols;
                break;
        }
        const std::uint32_t record[8] = {u32(lines.start), u32(lines.length), u32(blocks.start), u32(blocks.length),
                                         u32(half),        u32(sensor),       choice ? 0u : 1u,  0};
        write_record(int(u), slot, record);
    }
}

}  // namespace vkfuse::vk

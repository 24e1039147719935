// Tile-sparse fusion (SkipPolicy::Tiles) for periodization wavelets: a fused
// sensor whose changed tiles cover little of its frame computes only what
// those tiles' pixels need (core/sparse_wavelet.hpp plans it), and the rest of
// its result is its fused background.
//
//   per run, host, per fused slot j (sensor s):
//     changed tiles -> their rectangle R (circular rows x columns)
//     plan_sparse_wavelet(R): per level and pass, the lines and blocks to compute
//     -> region records [dispatch][slot] in a host-written buffer (full ones
//        for a slot fused whole); each dispatch's indirect grid cut to the
//        largest of its records
//   fusion command buffer, as recorded:
//     dwt_rows_frames / dwt_rows4 / dwt_forward   (forward rows,  region records)
//     dwt_fuse_columns                            (forward columns + fusion)
//     dwt_inverse x 2 per level                   (inverse columns, rows)
//     sparse_compose: outside R, slot j takes sensor s's fused background
//
// An invocation maps onto its slot's record's circular ranges
// (shaders/sparse.glsl) or leaves; the compose keeps its whole grid.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/sparse_wavelet.hpp"
#include "vk/engine/buffer.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::vk {

// How one region-aware dispatch maps the plan's ranges onto its invocations.
enum class SparsePass {
    ForwardRows,  // lines: rows of A_l; blocks: coefficient pairs along the row
    ForwardCols,  // lines: the row pass's columns, low and high halves; blocks: pair rows
    InverseCols,  // lines: the fused block's columns, both halves; blocks: coefficients o of the output rows
    InverseRows,  // lines: rows of A_l; blocks: coefficients o of the output columns
    Compose,      // lines: output rows; blocks: output columns (pixels)
};

struct SparseUse {
    SparsePass pass = SparsePass::Compose;
    int level = 0;
    int block = 1;  // outputs (pairs, coefficients, pixels) per invocation along the block axis
    // The dispatch's index in the recorded list (its indirect arguments):
    // a line kernel's 1-D grid of lines x blocks (sparse.glsl's line_item),
    // which shrink() sizes to the records. The compose keeps its grid.
    std::uint32_t dispatch = 0;
};

// Whether a plan can fuse sparsely: PlanConfig::skip Tiles on a periodization
// wavelet with float32 planes. Other tiles plans fuse changed sensors whole.
bool sparse_capable(const PlanConfig& cfg);

class SparseRegions {
public:
    SparseRegions(Context::Impl& ctx, const PlanConfig& cfg);

    // The push value `region` of a new region-aware dispatch (shaders/sparse.glsl).
    std::uint32_t declare(const SparseUse& use);
    DeviceSpan regions() const { return regions_.span(); }
    DeviceSpan backgrounds() const { return backgrounds_.span(); }

    // Sensor's fused background, planar (what sparse_compose fills in with).
    void set_background(int sensor, const Image& fused_background);
    // Before a run's write()s: no slot written yet.
    void begin_run();
    // Slot `slot` (sensor `sensor`) this run: fused whole (no choice), or only
    // what the chosen rectangle needs (core::choose_sparse).
    void write(int slot, int sensor, const std::optional<core::SparseChoice>& choice);
    // Each region-aware dispatch's grid cut to the largest of this run's
    // records (the rest of its invocations would only leave).
    void shrink(VkDispatchIndirectCommand* args) const;

private:
    PlanConfig cfg_;
    core::SparseChoice whole_;  // the plan of the whole frame: a slot fused whole
    std::vector<SparseUse> uses_;
    std::vector<std::array<std::uint32_t, 2>> extent_;  // per use, this run: most lines, most blocks
    Buffer regions_;      // [use][slot][8] uints, host-written
    Buffer backgrounds_;  // S*C planes of H x W, float32

    void write_record(int use, int slot, const std::uint32_t (&record)[8]);  // and its extent
};

}  // namespace vkfuse::vk

// core/sparse_wavelet.hpp - what a periodization wavelet fusion must compute
// for part of its output to equal full fusion there: the region planner for
// tile-sparse fusion (docs/spec.md, "Skipping"), its work model, and its CPU
// twin, which computes nothing outside the planned regions.
//
// A fused output pixel depends on the frames' samples within the wavelet's
// reach of it: the synthesis taps of every level it is rebuilt from, then the
// analysis taps of every level those coefficients came from, growing 2x per
// level and wrapping around the image's edges (periodization). The planner
// walks that chain backwards from an output rectangle, one pass at a time:
//
//   output rect R_0 (pixels)
//     <- inverse rows   l: A_l rows x cols        reads u_l  (rows, synthesis reach of cols)
//     <- inverse cols   l: A_l rows x pair cols   reads f_l  (synthesis reach of rows, cols)
//   f_l (coefficient pairs) = fused detail of level l, its approximation R_{l+1} (level l+1's
//   inverse output) or, at the deepest level, the fused approximation
//     <- forward cols + fuse l: pairs G_l = f_l and what level l+1's rows read of A_{l+1}
//                                reads t_l  (analysis reach of rows, cols)
//     <- forward rows   l: A_l rows x pair cols   reads A_l  (rows, analysis reach of cols)
//
// Every set is a rectangle of two circular index ranges (a range may wrap
// past the edge, as the periodic taps do). Each pass's range covers what the
// next one reads, so a pass that computes exactly its range reads only
// samples computed before it: the CPU twin checks that with NaN everywhere
// else.
#pragma once
#include <optional>
#include <vector>

#include "core/plane.hpp"
#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/skip.hpp"

namespace vkfuse::core {

// Indices start, start + 1, ... (mod n), `length` of them (0 <= length <= n).
struct CircularRange {
    int n = 0;
    int start = 0;
    int length = 0;
    bool contains(int i) const;
    bool full() const { return length == n; }
};

struct RangeRect {
    CircularRange rows, cols;
    double area() const { return double(rows.length) * double(cols.length); }
};

// One level's computed regions, each in the index space of the buffer it writes.
struct SparseWaveletLevel {
    int height = 0, width = 0;    // A_l
    int pair_rows = 0, pair_cols = 0;  // its coefficient pairs: ceil(height/2) x ceil(width/2)
    RangeRect forward_rows;  // rows of A_l x pair columns (of each frame's row pass)
    RangeRect forward_cols;  // pair rows x pair columns (each frame's coefficients, and the fused ones)
    RangeRect inverse_cols;  // rows of A_l x pair columns
    RangeRect inverse_rows;  // rows x columns of A_l
};

struct SparseWaveletPlan {
    std::vector<SparseWaveletLevel> levels;  // level 0 (full resolution) first
    RangeRect input;  // the frames' samples read: outside it nothing matters
    int filter_length = 0;
    // The multiply-adds of the planned passes over those of full fusion, for
    // K frames of C channels (forward passes x K C, inverse passes x C).
    double work_fraction(int frames, int channels) const;
};

// The plan that makes `output` (a rectangle of pixels of a height x width
// image) equal full fusion by spec. Periodization wavelets only: throws
// std::invalid_argument for any other method or mode.
SparseWaveletPlan plan_sparse_wavelet(const FusionSpec& spec, int height, int width, RangeRect output);

// The smallest circular range over n holding every marked index (marks.size() == n).
CircularRange cover(const std::vector<char>& marks);

// SkipPolicy::Tiles' choice for a changed sensor: the rectangle covering its
// changed tiles (kSkipTile a side, row-major, tiles_x across) and its plan,
// or nullopt where it is fused whole: the fusion is not a periodization
// wavelet, the rectangle is the frame, or the plan's work exceeds
// kMaxSparseWork of full fusion's (the halo covers most of the frame, and
// full fusion costs about the same).
inline constexpr double kMaxSparseWork = 0.85;
struct SparseChoice {
    RangeRect rect;
    SparseWaveletPlan plan;
};
std::optional<SparseChoice> choose_sparse(const FusionSpec& spec, int height, int width, int frames, int channels,
                                          const std::vector<bool>& changed_tiles, int tiles_x);
// What a changed sensor's cycle fuses: the choice's rectangle, or the whole
// height x width frame.
SkipRegion fused_region(const std::optional<SparseChoice>& choice, int height, int width);

// The CPU twin of a tile-sparse fusion: fuse_wavelet's arithmetic, computed
// only inside the plan's regions, NaN everywhere else. Inside the output
// rectangle it equals fuse_wavelet(frames, spec) bit for bit when the plan is
// right.
Plane fuse_wavelet_sparse(std::span<const Plane> frames, const FusionSpec& spec, const SparseWaveletPlan& plan);

}  // namespace vkfuse::core

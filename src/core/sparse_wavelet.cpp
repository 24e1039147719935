// The tile-sparse wavelet planner and its CPU twin (core/sparse_wavelet.hpp),
// with the periodization formulas of core/wavelet.hpp.
#include "core/sparse_wavelet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/method_table.hpp"
#include "core/rules.hpp"
#include "core/wavelet.hpp"
#include "core/wavelet_axis.hpp"
#include "vkfuse/core/skip.hpp"

namespace vkfuse::core {
namespace {

int mod(int a, int m) { return ((a % m) + m) % m; }

std::vector<char> marks_of(const CircularRange& r) {
    std::vector<char> m(std::size_t(r.n), 0);
    for (int i = 0; i < r.length; ++i) m[std::size_t(mod(r.start + i, r.n))] = 1;
    return m;
}

CircularRange united(const CircularRange& a, const CircularRange& b) {
    std::vector<char> m = marks_of(a);
    for (int i = 0; i < b.length; ++i) m[std::size_t(mod(b.start + i, b.n))] = 1;
    return cover(m);
}

// The inputs (of `inputs`) that the table's outputs in `out` read.
CircularRange reads(const LineGather& g, const CircularRange& out, int inputs) {
    std::vector<char> m(std::size_t(inputs), 0);
    for (int i = 0; i < out.length; ++i) {
        const std::size_t o = std::size_t(mod(out.start + i, out.n)) * std::size_t(g.taps);
        for (int t = 0; t < g.taps; ++t) m[std::size_t(g.index[o + std::size_t(t)])] = 1;
    }
    return cover(m);
}

// The samples of a line of n that analysis outputs `out` (pairs) read.
CircularRange analysis_reads(const CircularRange& out, int n, const FilterBank& fb) {
    return reads(periodization_analysis(fb.dec_lo, fb.length, n), out, n);
}

// The coefficients (of a band of `pairs`) that synthesis outputs `out` read.
CircularRange synthesis_reads(const CircularRange& out, int pairs, const FilterBank& fb) {
    return reads(periodization_synthesis(fb.rec_lo, fb.length, pairs), out, pairs);
}

// Output o of table g, its inputs read through at(i).
template <class At>
double gathered(const LineGather& g, int o, At at) {
    double v = 0;
    const std::size_t first = std::size_t(o) * std::size_t(g.taps);
    for (std::size_t t = first; t < first + std::size_t(g.taps); ++t) v += g.weight[t] * at(g.index[t]);
    return v;
}

template <class F>
void each(const CircularRange& r, F f) {
    for (int i = 0; i < r.length; ++i) f(mod(r.start + i, r.n));
}

Plane nan_plane(int h, int w) {
    Plane p(h, w);
    std::fill(p.data.begin(), p.data.end(), std::numeric_limits<double>::quiet_NaN());
    return p;
}

}  // namespace

bool CircularRange::contains(int i) const { return length > 0 && mod(i - start, n) < length; }

CircularRange cover(const std::vector<char>& marks) {
    const int n = int(marks.size());
    int first = -1;
    for (int i = 0; i < n; ++i)
        if (marks[std::size_t(i)]) {
            first = i;
            break;
        }
    if (first < 0) return {n, 0, 0};
    // The longest circular run of unmarked indices; the cover is the rest.
    int best_gap = 0, best_end = first, gap = 0;
    for (int step = 1; step <= n; ++step) {
        const int i = (first + step) % n;
        if (!marks[std::size_t(i)]) {
            ++gap;
            continue;
        }
        if (gap > best_gap) {
            best_gap = gap;
            best_end = i;
        }
        gap = 0;
    }
    return {n, best_gap == 0 ? 0 : best_end, n - best_gap};
}

std::optional<SparseChoice> choose_sparse(const FusionSpec& spec, int H, int W, int frames, int channels,
                                          const std::vector<bool>& changed, int tiles_x) {
    if (!fuses_tile_sparse(spec)) return std::nullopt;
    std::vector<char> rows(std::size_t(H), 0), cols(std::size_t(W), 0);
    for (std::size_t t = 0; t < changed.size(); ++t) {
        if (!changed[t]) continue;
        const int ty = int(t) / tiles_x, tx = int(t) % tiles_x;
        for (int y = ty * kSkipTile; y < std::min(H, (ty + 1) * kSkipTile); ++y) rows[std::size_t(y)] = 1;
        for (int x = tx * kSkipTile; x < std::min(W, (tx + 1) * kSkipTile); ++x) cols[std::size_t(x)] = 1;
    }
    SparseChoice choice{{cover(rows), cover(cols)}, {}};
    if (choice.rect.rows.full() && choice.rect.cols.full()) return std::nullopt;
    choice.plan = plan_sparse_wavelet(spec, H, W, choice.rect);
    if (choice.plan.work_fraction(frames, channels) > kMaxSparseWork) return std::nullopt;
    return choice;
}

SkipRegion fused_region(const std::optional<SparseChoice>& choice, int height, int width) {
    if (!choice) return {0, height, 0, width};
    const RangeRect& r = choice->rect;
    return {r.rows.start, r.rows.length, r.cols.start, r.cols.length};
}

double SparseWaveletPlan::work_fraction(int frames, int channels) const {
    const int F = filter_length;
    const double forward = double(frames) * channels * 2 * F, inverse = double(channels) * F;
    double sparse = 0, full = 0;
    for (const SparseWaveletLevel& l : levels) {
        // Forward rows: a pair per (row, pair column); columns + fusion: a
        // pair per (pair row, t column), two t columns per pair column.
        // Inverse columns: one output per (row, u column), two u columns per
        // pair column; inverse rows: one per pixel. Each output costs its
        // filter's taps (F for a pair of analysis outputs, F / 2 x 2 bands for
        // a synthesis output).
        sparse += forward * (l.forward_rows.area() + 2 * l.forward_cols.area());
        sparse += inverse * (2 * l.inverse_cols.area() + l.inverse_rows.area());
        full += forward * (double(l.height) * l.pair_cols + 2.0 * l.pair_rows * l.pair_cols);
        full += inverse * (2.0 * l.height * l.pair_cols + double(l.height) * l.width);
    }
    return full > 0 ? sparse / full : 0;
}

SparseWaveletPlan plan_sparse_wavelet(const FusionSpec& spec, int height, int width, RangeRect output) {
    if (!fuses_tile_sparse(spec))
        throw std::invalid_argument("plan_sparse_wavelet: " + std::string(to_string(spec.method)) +
                                    " is not fused tile-sparsely (its method row)");
    const FilterBank& fb = filter_bank(spec.wavelet);
    const int L = spec.effective_levels();
    SparseWaveletPlan plan;
    plan.filter_length = fb.length;
    for (int l = 0, h = height, w = width; l < L; ++l, h = (h + 1) / 2, w = (w + 1) / 2)
        plan.levels.push_back({h, w, (h + 1) / 2, (w + 1) / 2, {}, {}, {}, {}});
    // Inverse, from the output up to the deepest level: what each pass computes.
    std::vector<RangeRect> fused(static_cast<std::size_t>(L));  // f_l, in pairs
    RangeRect need = output;
    for (int l = 0; l < L; ++l) {
        SparseWaveletLevel& lv = plan.levels[std::size_t(l)];
        lv.inverse_rows = need;
        lv.inverse_cols = {need.rows, synthesis_reads(need.cols, lv.pair_cols, fb)};
        fused[std::size_t(l)] = {synthesis_reads(need.rows, lv.pair_rows, fb), lv.inverse_cols.cols};
        need = fused[std::size_t(l)];  // its approximation is A_{l+1}, level l + 1's inverse output
    }
    // Forward, from the deepest level down: each level's pairs cover its own
    // fused pairs and what the level below reads of its approximation.
    RangeRect below_reads{};
    for (int l = L - 1; l >= 0; --l) {
        SparseWaveletLevel& lv = plan.levels[std::size_t(l)];
        RangeRect pairs = fused[std::size_t(l)];
        if (l < L - 1) pairs = {united(pairs.rows, below_reads.rows), united(pairs.cols, below_reads.cols)};
        lv.forward_cols = pairs;
        lv.forward_rows = {analysis_reads(pairs.rows, lv.height, fb), pairs.cols};
        below_reads = {lv.forward_rows.rows, analysis_reads(pairs.cols, lv.width, fb)};
    }
    plan.input = below_reads;
    return plan;
}

Plane fuse_wavelet_sparse(std::span<const Plane> frames, const FusionSpec& spec, const SparseWaveletPlan& plan) {
    const FilterBank& fb = filter_bank(spec.wavelet);
    const int F = fb.length, L = int(plan.levels.size()), K = int(frames.size());
    // Forward: per level and frame, rows then columns, only inside the plan.
    std::vector<Plane> approx(frames.begin(), frames.end());
    std::vector<Plane> fused_blocks;  // per level: 2 pair_rows x 2 pair_cols, [lo | hi] both ways
    for (int l = 0; l < L; ++l) {
        const SparseWaveletLevel& lv = plan.levels[std::size_t(l)];
        const int n_rows = lv.height, n_cols = lv.width, pr = lv.pair_rows, pc = lv.pair_cols;
        const LineGather row_lo = periodization_analysis(fb.dec_lo, F, n_cols),
                         row_hi = periodization_analysis(fb.dec_hi, F, n_cols),
                         col_lo = periodization_analysis(fb.dec_lo, F, n_rows),
                         col_hi = periodization_analysis(fb.dec_hi, F, n_rows);
        std::vector<Plane> blocks;
        for (int k = 0; k < K; ++k) {
            const Plane& a = approx[std::size_t(k)];
            Plane t = nan_plane(n_rows, 2 * pc);
            each(lv.forward_rows.rows, [&](int r) {
                const auto sample = [&](int x) { return a.at(r, x); };
                each(lv.forward_rows.cols, [&](int o) {
                    t.at(r, o) = gathered(row_lo, o, sample);
                    t.at(r, pc + o) = gathered(row_hi, o, sample);
                });
            });
            Plane d = nan_plane(2 * pr, 2 * pc);
            each(lv.forward_cols.rows, [&](int o) {
                each(lv.forward_cols.cols, [&](int oc) {
                    for (int c : {oc, pc + oc}) {
                        const auto sample = [&](int y) { return t.at(y, c); };
                        d.at(o, c) = gathered(col_lo, o, sample);
                        d.at(pr + o, c) = gathered(col_hi, o, sample);
                    }
                });
            });
            blocks.push_back(std::move(d));
        }
        // Fusion inside the plan: the detail quadrants everywhere, the
        // approximation only at the deepest level (above it, the inverse
        // rebuilds it); the next level's input is each frame's approximation.
        Plane f = nan_plane(2 * pr, 2 * pc);
        std::vector<double> values(static_cast<std::size_t>(K));
        each(lv.forward_cols.rows, [&](int o) {
            each(lv.forward_cols.cols, [&](int oc) {
                for (int qr = 0; qr < 2; ++qr)
                    for (int qc = 0; qc < 2; ++qc) {
                        const bool approximation = qr == 0 && qc == 0;
                        if (approximation && l < L - 1) continue;
                        for (int k = 0; k < K; ++k) values[std::size_t(k)] = blocks[std::size_t(k)].at(qr * pr + o, qc * pc + oc);
                        f.at(qr * pr + o, qc * pc + oc) =
                            combine(approximation ? spec.base_rule : spec.detail_rule, values);
                    }
            });
        });
        fused_blocks.push_back(std::move(f));
        for (int k = 0; k < K; ++k) {
            Plane next(pr, pc);
            for (int y = 0; y < pr; ++y)
                for (int x = 0; x < pc; ++x) next.at(y, x) = blocks[std::size_t(k)].at(y, x);
            approx[std::size_t(k)] = std::move(next);
        }
    }
    // Inverse, deepest level first: columns, then rows, only inside the plan.
    Plane a;
    for (int l = L - 1; l >= 0; --l) {
        const SparseWaveletLevel& lv = plan.levels[std::size_t(l)];
        const int pr = lv.pair_rows, pc = lv.pair_cols;
        Plane& f = fused_blocks[std::size_t(l)];
        if (l < L - 1)
            for (int y = 0; y < pr; ++y)
                for (int x = 0; x < pc; ++x) f.at(y, x) = a.at(y, x);
        const LineGather col_lo = periodization_synthesis(fb.rec_lo, F, pr),
                         col_hi = periodization_synthesis(fb.rec_hi, F, pr),
                         row_lo = periodization_synthesis(fb.rec_lo, F, pc),
                         row_hi = periodization_synthesis(fb.rec_hi, F, pc);
        Plane u = nan_plane(lv.height, 2 * pc);
        each(lv.inverse_cols.rows, [&](int n) {
            each(lv.inverse_cols.cols, [&](int oc) {
                for (int c : {oc, pc + oc})
                    u.at(n, c) = gathered(col_lo, n, [&](int i) { return f.at(i, c); }) +
                                 gathered(col_hi, n, [&](int i) { return f.at(pr + i, c); });
            });
        });
        Plane out = nan_plane(lv.height, lv.width);
        each(lv.inverse_rows.rows, [&](int r) {
            each(lv.inverse_rows.cols, [&](int n) {
                out.at(r, n) = gathered(row_lo, n, [&](int i) { return u.at(r, i); }) +
                               gathered(row_hi, n, [&](int i) { return u.at(r, pc + i); });
            });
        });
        a = std::move(out);
    }
    return a;
}

}  // namespace vkfuse::core

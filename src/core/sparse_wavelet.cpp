// The tile-sparse wavelet planner and its CPU twin (core/sparse_wavelet.hpp),
// with the periodization formulas of core/wavelet.hpp.
#include "core/sparse_wavelet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/rules.hpp"
#include "core/wavelet.hpp"
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

// The samples of a line of n that analysis outputs `out` (pairs) read.
CircularRange analysis_reads(const CircularRange& out, int n, int F) {
    const int padded = n + n % 2;
    std::vector<char> m(std::size_t(n), 0);
    for (int i = 0; i < out.length; ++i) {
        const int o = mod(out.start + i, out.n);
        for (int j = 0; j < F; ++j) m[std::size_t(std::min(mod(2 * o + F / 2 - j, padded), n - 1))] = 1;
    }
    return cover(m);
}

// The coefficients (of a band of `pairs`) that synthesis outputs `out` read.
CircularRange synthesis_reads(const CircularRange& out, int pairs, int F) {
    const int half = F / 2, start = F / 4, shift = half % 2 == 0 ? 1 : 0;
    std::vector<char> m(std::size_t(pairs), 0);
    for (int i = 0; i < out.length; ++i) {
        const int q = mod(mod(out.start + i, out.n) - shift, 2 * pairs), c = q / 2;
        for (int j = 0; j < half; ++j) m[std::size_t(mod(c + start - j, pairs))] = 1;
    }
    return cover(m);
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
    if (spec.method != Method::Wavelet || spec.mode != WaveletMode::Periodization) return std::nullopt;
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
    if (spec.method != Method::Wavelet || spec.mode != WaveletMode::Periodization)
        throw std::invalid_argument("plan_sparse_wavelet: periodization wavelets only");
    const int F = filter_bank(spec.wavelet).length, L = spec.effective_levels();
    SparseWaveletPlan plan;
    plan.filter_length = F;
    for (int l = 0, h = height, w = width; l < L; ++l, h = (h + 1) / 2, w = (w + 1) / 2)
        plan.levels.push_back({h, w, (h + 1) / 2, (w + 1) / 2, {}, {}, {}, {}});
    // Inverse, from the output up to the deepest level: what each pass computes.
    std::vector<RangeRect> fused(static_cast<std::size_t>(L));  // f_l, in pairs
    RangeRect need = output;
    for (int l = 0; l < L; ++l) {
        SparseWaveletLevel& lv = plan.levels[std::size_t(l)];
        lv.inverse_rows = need;
        lv.inverse_cols = {need.rows, synthesis_reads(need.cols, lv.pair_cols, F)};
        fused[std::size_t(l)] = {synthesis_reads(need.rows, lv.pair_rows, F), lv.inverse_cols.cols};
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
        lv.forward_rows = {analysis_reads(pairs.rows, lv.height, F), pairs.cols};
        below_reads = {lv.forward_rows.rows, analysis_reads(pairs.cols, lv.width, F)};
    }
    plan.input = below_reads;
    return plan;
}

Plane fuse_wavelet_sparse(std::span<const Plane> frames, const FusionSpec& spec, const SparseWaveletPlan& plan) {
    const FilterBank& fb = filter_bank(spec.wavelet);
    const int F = fb.length, half = F / 2, start = F / 4, shift = half % 2 == 0 ? 1 : 0;
    const int L = int(plan.levels.size()), K = int(frames.size());
    // Forward: per level and frame, rows then columns, only inside the plan.
    std::vector<Plane> approx(frames.begin(), frames.end());
    std::vector<Plane> fused_blocks;  // per level: 2 pair_rows x 2 pair_cols, [lo | hi] both ways
    for (int l = 0; l < L; ++l) {
        const SparseWaveletLevel& lv = plan.levels[std::size_t(l)];
        const int n_rows = lv.height, n_cols = lv.width, pr = lv.pair_rows, pc = lv.pair_cols;
        std::vector<Plane> blocks;
        for (int k = 0; k < K; ++k) {
            const Plane& a = approx[std::size_t(k)];
            Plane t = nan_plane(n_rows, 2 * pc);
            each(lv.forward_rows.rows, [&](int r) {
                each(lv.forward_rows.cols, [&](int o) {
                    double lo = 0, hi = 0;
                    for (int j = 0; j < F; ++j) {
                        const double x = a.at(r, std::min(mod(2 * o + F / 2 - j, n_cols + n_cols % 2), n_cols - 1));
                        lo += fb.dec_lo[std::size_t(j)] * x;
                        hi += fb.dec_hi[std::size_t(j)] * x;
                    }
                    t.at(r, o) = lo;
                    t.at(r, pc + o) = hi;
                });
            });
            Plane d = nan_plane(2 * pr, 2 * pc);
            each(lv.forward_cols.rows, [&](int o) {
                each(lv.forward_cols.cols, [&](int oc) {
                    for (int c : {oc, pc + oc}) {
                        double lo = 0, hi = 0;
                        for (int j = 0; j < F; ++j) {
                            const double x = t.at(std::min(mod(2 * o + F / 2 - j, n_rows + n_rows % 2), n_rows - 1), c);
                            lo += fb.dec_lo[std::size_t(j)] * x;
                            hi += fb.dec_hi[std::size_t(j)] * x;
                        }
                        d.at(o, c) = lo;
                        d.at(pr + o, c) = hi;
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
        Plane u = nan_plane(lv.height, 2 * pc);
        each(lv.inverse_cols.rows, [&](int n) {
            const int q = mod(n - shift, 2 * pr), m = q / 2, p = q % 2;
            each(lv.inverse_cols.cols, [&](int oc) {
                for (int c : {oc, pc + oc}) {
                    double v = 0;
                    for (int j = 0; j < half; ++j) {
                        const int i = mod(m + start - j, pr);
                        v += fb.rec_lo[std::size_t(2 * j + p)] * f.at(i, c) + fb.rec_hi[std::size_t(2 * j + p)] * f.at(pr + i, c);
                    }
                    u.at(n, c) = v;
                }
            });
        });
        Plane out = nan_plane(lv.height, lv.width);
        each(lv.inverse_rows.rows, [&](int r) {
            each(lv.inverse_rows.cols, [&](int n) {
                const int q = mod(n - shift, 2 * pc), m = q / 2, p = q % 2;
                double v = 0;
                for (int j = 0; j < half; ++j) {
                    const int i = mod(m + start - j, pc);
                    v += fb.rec_lo[std::size_t(2 * j + p)] * u.at(r, i) + fb.rec_hi[std::size_t(2 * j + p)] * u.at(r, pc + i);
                }
                out.at(r, n) = v;
            });
        });
        a = std::move(out);
    }
    return a;
}

}  // namespace vkfuse::core

// Wavelet fusion: per level, a row pass and a column pass of the 1-D DWT over
// every frame's planes, fusion of that level's coefficients across frames,
// then the inverse from the coarsest level down. Periodization uses pywt's
// convolution formulas (dwt_forward/dwt_inverse.comp), symmetric mode the
// lifting schemes (lift_forward/lift_inverse.comp), both from core/wavelet.hpp.
//
// Level l splits A_l (h x w) into a block D_l of bh x bw holding the
// approximation (top-left ch x cw, which is A_{l+1}) and the detail bands.
// Periodization blocks are 2ch x 2cw (odd sizes padded as pywt does);
// symmetric blocks are exactly h x w.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <vector>

#include "core/wavelet.hpp"
#include "vk/passes/graph.hpp"
#include "vk/passes/plan_sparse.hpp"

namespace vkfuse::vk {
namespace {

struct LevelShape {
    int h, w;    // the approximation this level splits
    int ch, cw;  // its approximation (next level's input)
    int bh, bw;  // coefficient block
};

struct LineSpec {  // one 1-D pass: `lines` lines of n samples
    int n, half_len, high_len, lines;
    bool along_rows;  // true: lines are rows; false: columns
};

// The lifting scheme as lifting.glsl reads it: [steps, Ke, Ko, 1/Ke as a
// float pair (high, low), 1/Ko likewise, then per step: parity, taps, c0, c1,
// o0, o1]. The inverse scales by the reciprocals in compensated arithmetic,
// since a GPU's float division may be off by 2.5 ulps (SPIR-V's OpFDiv).
std::vector<float> lifting_constants(Wavelet w) {
    constexpr std::size_t kSteps = 7;  // where the steps begin
    std::vector<float> c(kSteps + 24, 0.0f);
    const auto& ls = core::lifting_scheme(w);
    c[0] = float(ls.steps);
    c[1] = float(ls.scale_even);
    c[2] = float(ls.scale_odd);
    for (std::size_t i = 0; i < 2; ++i) {
        const double inverse = 1.0 / double(c[1 + i]);  // of the float the forward pass multiplies by
        c[3 + 2 * i] = float(inverse);
        c[4 + 2 * i] = float(inverse - double(float(inverse)));
    }
    for (int s = 0; s < ls.steps; ++s) {
        const auto& st = ls.step[std::size_t(s)];
        float* o = &c[kSteps + 6 * std::size_t(s)];
        o[0] = float(st.parity);
        o[1] = float(st.taps);
        o[2] = float(st.coef[0]);
        o[3] = float(st.coef[1]);
        o[4] = float(st.offset[0]);
        o[5] = float(st.offset[1]);
    }
    return c;
}

// How far the filter bank, as the kernels hold it, is from perfect
// reconstruction: the largest entry of synthesis x analysis - identity on a
// periodic line of 32 samples, computed in double from the taps rounded to
// float (analysis taps times s, synthesis taps divided by s).
double reconstruction_error(const core::FilterBank& fb, double s) {
    constexpr int N = 32, M = N / 2;
    const int F = fb.length, Hf = F / 2, start = F / 4, shift = Hf % 2 == 0 ? 1 : 0;
    const auto as_float = [](double v) { return double(float(v)); };
    const auto wrap = [](int a, int n) { return ((a % n) + n) % n; };
    std::vector<double> analysis(N * N, 0.0), synthesis(N * N, 0.0);
    for (int o = 0; o < M; ++o)
        for (int j = 0; j < F; ++j) {
            const int col = wrap(F / 2 + 2 * o - j, N);
            analysis[std::size_t(o * N + col)] += as_float(fb.dec_lo[std::size_t(j)] * s);
            analysis[std::size_t((M + o) * N + col)] += as_float(fb.dec_hi[std::size_t(j)] * s);
        }
    for (int m = 0; m < N; ++m) {
        const int q = wrap(m - shift, N), o = q / 2, p = q % 2;
        for (int j = 0; j < Hf; ++j) {
            const int k = wrap(o + start - j, M);
            synthesis[std::size_t(m * N + k)] += as_float(fb.rec_lo[std::size_t(2 * j + p)] / s);
            synthesis[std::size_t(m * N + M + k)] += as_float(fb.rec_hi[std::size_t(2 * j + p)] / s);
        }
    }
    double worst = 0;
    for (int r = 0; r < N; ++r)
        for (int c = 0; c < N; ++c) {
            double v = r == c ? -1.0 : 0.0;
            for (int k = 0; k < N; ++k) v += synthesis[std::size_t(r * N + k)] * analysis[std::size_t(k * N + c)];
            worst = std::max(worst, std::abs(v));
        }
    return worst;
}

// A scale s for the analysis taps (synthesis taps get 1 / s). Any s > 0
// leaves the fused image unchanged in exact arithmetic: every coefficient of
// a band is scaled alike in every frame, which no rule notices, and the
// inverse undoes it. In float32 it matters: pywt's taps carry sqrt(2), and
// rounded to float they reconstruct with a gain of 1 - 3.4e-8 (haar) per
// 1-D pass, which a rig re-fusing its own output compounds (the stress
// suite's 100 feedback passes drifted by 4e-5). Without the sqrt(2), haar's
// and bior2.2's taps are dyadic fractions, exact in float, and bior4.4's
// error drops from 2.8e-8 to 6e-9; db2 is better as pywt has it. So each
// wavelet takes whichever of the two is closer to perfect reconstruction.
double analysis_scale(const core::FilterBank& fb) {
    const double unnormalised = 1.0 / std::sqrt(2.0);
    return reconstruction_error(fb, unnormalised) <= reconstruction_error(fb, 1.0) ? unnormalised : 1.0;
}

// filter_taps.glsl's specialization constants: F, then dec_lo, dec_hi,
// rec_lo, rec_hi (10 taps each), scaled by analysis_scale().
std::vector<std::uint32_t> filter_specialization(Wavelet w) {
    using Taps = decltype(core::FilterBank::dec_lo);
    static_assert(1 + 4 * std::tuple_size_v<Taps> == VKFUSE_FILTER_CONSTANTS, "filter_taps.glsl's constant_ids");
    const auto& fb = core::filter_bank(w);
    const double s = analysis_scale(fb);
    std::vector<std::uint32_t> words{std::uint32_t(fb.length)};
    for (const auto* taps : {&fb.dec_lo, &fb.dec_hi})
        for (double t : *taps) words.push_back(std::bit_cast<std::uint32_t>(float(t * s)));
    for (const auto* taps : {&fb.rec_lo, &fb.rec_hi})
        for (double t : *taps) words.push_back(std::bit_cast<std::uint32_t>(float(t / s)));
    return words;
}

// Outputs (forward: coefficient pairs; inverse: coefficient indices o) per
// invocation of dwt_forward / dwt_inverse.
constexpr int kConvBlock = VKFUSE_CONV_BLOCK;
// Pixels of a row per invocation of sparse_compose.
constexpr std::uint32_t kComposeSpan = VKFUSE_COMPOSE_SPAN;
// Coefficient pairs per invocation of the row passes of whole quads.
constexpr int kRowPairs = VKFUSE_ROW_PAIRS;

std::vector<LevelShape> level_shapes(const PlanConfig& cfg) {
    const bool periodization = cfg.fusion.mode == WaveletMode::Periodization;
    std::vector<LevelShape> shapes;
    int h = cfg.height, w = cfg.width;
    for (int l = 0; l < cfg.fusion.effective_levels(); ++l) {
        LevelShape s{h, w, (h + 1) / 2, (w + 1) / 2, 0, 0};
        s.bh = periodization ? 2 * s.ch : h;
        s.bw = periodization ? 2 * s.cw : w;
        shapes.push_back(s);
        h = s.ch;
        w = s.cw;
    }
    return shapes;
}

class WaveletGraph {
public:
    WaveletGraph(GraphBuilder& g) : g_(g), spec_(g.cfg.fusion) {
        periodization_ = spec_.mode == WaveletMode::Periodization;
        if (periodization_)
            taps_ = filter_specialization(spec_.wavelet);
        else
            scheme_ = g.constants(lifting_constants(spec_.wavelet));
        shapes_ = level_shapes(g.cfg);
    }

    VkDeviceAddress record(FrameSource& input) {
        const auto& top = shapes_.front();
        const VkDeviceAddress scratch = g_.planes(std::uint64_t(g_.planes_in()) * top.h * top.bw);
        std::vector<PlaneView> fused;
        PlaneView a;
        const int L = int(shapes_.size());
        for (int l = 0; l < L; ++l) {
            const auto& s = shapes_[std::size_t(l)];
            PlaneView t{scratch, s.bw, std::uint32_t(s.h * s.bw)};
            PlaneView d{g_.planes(std::uint64_t(g_.planes_in()) * s.bh * s.bw), s.bw, std::uint32_t(s.bh * s.bw)};
            rows(input, a, t, l);
            PlaneView f{g_.planes(std::uint64_t(g_.planes_out()) * s.bh * s.bw), s.bw, std::uint32_t(s.bh * s.bw)};
            if (periodization_) {
                fuse_columns(t, d, f, s, l, l == L - 1);
            } else {
                columns(t, d, s);
                fuse(d, f, s, l == L - 1);
            }
            fused.push_back(f);
            a = {d.addr, s.bw, d.plane_stride};
        }
        g_.rec.mark("dwt_and_fuse");
        return invert(fused);
    }

    // Every frame's coefficient blocks, level by level (planes_in() blocks
    // of each level's shape), for fuse_cached to fuse in any combination.
    std::vector<PlaneView> decompose(FrameSource& input) {
        const auto& top = shapes_.front();
        const VkDeviceAddress scratch = g_.planes(std::uint64_t(g_.planes_in()) * top.h * top.bw);
        std::vector<PlaneView> levels;
        PlaneView a;
        for (std::size_t l = 0; l < shapes_.size(); ++l) {
            const auto& s = shapes_[l];
            const PlaneView t{scratch, s.bw, std::uint32_t(s.h * s.bw)};
            const PlaneView d{g_.planes(std::uint64_t(g_.planes_in()) * s.bh * s.bw), s.bw, std::uint32_t(s.bh * s.bw)};
            rows(input, a, t, int(l));
            columns(t, d, s);
            levels.push_back(d);
            a = d;
        }
        g_.rec.mark("dwt");
        return levels;
    }

    // The plan's sensors (blocks of `sources`) fused from decompose()'s
    // blocks of each group of sources: sensor j's frame k is block
    // table[j*K + k] of its group's levels.
    VkDeviceAddress fuse_cached(std::span<const CachedSources> groups, std::uint32_t sources, DeviceSpan table) {
        std::vector<PlaneView> fused;
        for (const auto& s : shapes_)
            fused.push_back({g_.planes(std::uint64_t(g_.planes_out()) * s.bh * s.bw), s.bw, std::uint32_t(s.bh * s.bw)});
        for (const CachedSources& group : groups)
            for (std::size_t l = 0; l < shapes_.size(); ++l) {
                const auto& s = shapes_[l];
                const bool deepest = l + 1 == shapes_.size();
                // Above the deepest level the approximation corner is the inverse's to write.
                record_rule_fuse(g_, {group.levels[l], fused[l], s.bw, s.bh, deepest ? s.cw : 0, deepest ? s.ch : 0,
                                      table, deepest ? 0 : s.cw, deepest ? 0 : s.ch,
                                      SensorGroup{group.first, group.count, sources}});
            }
        g_.rec.mark("fuse");
        return invert(fused);
    }

private:
    GraphBuilder& g_;
    const FusionSpec& spec_;
    bool periodization_ = true;
    VkDeviceAddress scheme_ = 0;  // symmetric mode: the lifting scheme
    std::vector<std::uint32_t> taps_;
    std::vector<LevelShape> shapes_;

    int high(int n, int half) const { return periodization_ ? half : n - half; }

    // Level l's row pass into t: from the frames as uploaded (level 0, where
    // they suit dwt_rows_frames), from their unpacked planes, or from `a`,
    // the approximation the level above left.
    void rows(FrameSource& input, PlaneView& a, const PlaneView& t, int l) {
        const auto& s = shapes_[std::size_t(l)];
        const LineSpec ls{s.w, s.cw, high(s.w, s.cw), s.h, true};
        if (l == 0 && rows_from_frames(ls)) return forward_from_frames(input, t, ls);
        if (l == 0) a = {input.planes(), g_.cfg.width, std::uint32_t(g_.cfg.width * g_.cfg.height)};
        forward(a, t, ls, g_.planes_in(), l);
    }
    // A level's column pass over every frame's rows, whole blocks into d.
    void columns(const PlaneView& t, const PlaneView& d, const LevelShape& s) {
        forward(t, d, {s.h, s.ch, high(s.h, s.ch), s.bw, false}, g_.planes_in(), -1);
    }

    // The inverse from the coarsest fused level down; returns the fused planes.
    VkDeviceAddress invert(std::vector<PlaneView>& fused) {
        const auto& top = shapes_.front();
        const VkDeviceAddress out_addr = g_.planes(std::uint64_t(g_.planes_out()) * g_.cfg.width * g_.cfg.height);
        const VkDeviceAddress inv_scratch = g_.planes(std::uint64_t(g_.planes_out()) * top.h * top.bw);
        for (int l = int(shapes_.size()) - 1; l >= 0; --l) {
            const auto& s = shapes_[std::size_t(l)];
            PlaneView u{inv_scratch, s.bw, std::uint32_t(s.h * s.bw)};
            PlaneView dst = l > 0 ? fused[std::size_t(l) - 1]
                                 : PlaneView{out_addr, g_.cfg.width, std::uint32_t(g_.cfg.width * g_.cfg.height)};
            inverse(fused[std::size_t(l)], u, {s.h, s.ch, high(s.h, s.ch), s.bw, false},
                    region(SparsePass::InverseCols, l, kConvBlock));
            inverse(u, dst, {s.w, s.cw, high(s.w, s.cw), s.h, true}, region(SparsePass::InverseRows, l, kConvBlock));
        }
        g_.rec.mark("idwt");
        if (g_.sparse) compose(out_addr);
        return out_addr;
    }

    // A region-aware dispatch's push value and records (shaders/sparse.glsl):
    // none (0, any buffer bound in its place) unless the plan fuses sparsely.
    struct Region {
        std::uint32_t push = 0;
        std::optional<DeviceSpan> records;
        DeviceSpan or_else(DeviceSpan unused) const { return records ? *records : unused; }
    };
    Region region(SparsePass pass, int level, int block) {
        if (!g_.sparse) return {};
        const std::uint32_t next = std::uint32_t(g_.rec.sensor_dispatches().size());
        return {g_.sparse->declare({pass, level, block, next}), g_.sparse->regions()};
    }

    // Outside the rectangle each sparsely fused slot computed, its fused background.
    void compose(VkDeviceAddress out) {
        const Region r = region(SparsePass::Compose, 0, 1);
        g_.rec.dispatch("sparse_compose", {g_.span(out), g_.sparse->backgrounds(), *r.records},
                        PushConstants()
                            .u32("region", r.push)
                            .u32("slot_planes", std::uint32_t(g_.cfg.channels))
                            .i32("width", g_.cfg.width)
                            .i32("height", g_.cfg.height),
                        Recorder::Work{groups(std::uint32_t(g_.cfg.width), kComposeSpan), std::uint32_t(g_.cfg.height),
                                       g_.planes_out()});
        g_.rec.mark("sparse_compose");
    }

    PushConstants line_push(const PlaneView& src, const PlaneView& dst, const LineSpec& ls) const {
        // Along rows: next line is a row below, next sample is adjacent.
        // Along columns: next line is adjacent, next sample is a row below.
        const int s_line = ls.along_rows ? src.row_stride : 1, s_elem = ls.along_rows ? 1 : src.row_stride;
        const int d_line = ls.along_rows ? dst.row_stride : 1, d_elem = ls.along_rows ? 1 : dst.row_stride;
        return PushConstants()
            .i32("n", ls.n)
            .i32("half_len", ls.half_len)
            .i32("high_len", ls.high_len)
            .i32("lines", ls.lines)
            .i32("src_line_stride", s_line)
            .i32("src_elem_stride", s_elem)
            .u32("src_plane_stride", src.plane_stride)
            .i32("dst_line_stride", d_line)
            .i32("dst_elem_stride", d_elem)
            .u32("dst_plane_stride", dst.plane_stride)
            .u32("lines_fastest", ls.along_rows ? 0 : 1);
    }

    // Lifting: an invocation per line. Convolution: per line, an invocation
    // per kConvBlock of the half_len coefficient positions.
    void dispatch_line(const char* conv, const char* lift, const PlaneView& src, const PlaneView& dst, const LineSpec& ls,
                       std::uint32_t planes, const Region& r) {
        const auto push =
            line_push(src, dst, ls).u32("region", r.push).u32("slot_planes", planes / std::uint32_t(g_.cfg.sensors));
        const DeviceSpan in = g_.span(src.addr), out = g_.span(dst.addr), scheme = scheme_ ? g_.span(scheme_) : in;
        const DeviceSpan records = r.or_else(in);
        const std::uint32_t blocks = groups(std::uint32_t(ls.half_len), kConvBlock);
        if (!periodization_) {
            g_.rec.dispatch(lift, {in, out, scheme, records}, push, Recorder::Work{std::uint32_t(ls.lines), 1, planes});
        } else {
            g_.rec.dispatch(conv, {in, out, scheme, records}, push,
                            Recorder::LinearWork{std::uint64_t(blocks) * std::uint64_t(ls.lines), planes}, taps_);
        }
    }

    // The first row pass reads the frames as uploaded where its rows are whole
    // quads of pixels and its pairs come eight at a time.
    bool rows_from_frames(const LineSpec& ls) const {
        return periodization_ && ls.half_len % kRowPairs == 0 && ls.n % 4 == 0;
    }
    void forward_from_frames(const FrameSource& input, const PlaneView& dst, const LineSpec& ls) {
        const Region r = region(SparsePass::ForwardRows, 0, kRowPairs);
        g_.rec.dispatch("dwt_rows_frames",
                        {input.frames(), input.frames(), g_.span(dst.addr), r.or_else(input.frames())},
                        input.frame_fields()
                            .i32("n", ls.n)
                            .i32("half_len", ls.half_len)
                            .i32("lines", ls.lines)
                            .i32("dst_row_stride", dst.row_stride)
                            .u32("dst_plane_stride", dst.plane_stride)
                            .u32("region", r.push)
                            .u32("slot_planes", std::uint32_t(g_.cfg.frames)),
                        Recorder::LinearWork{std::uint64_t(ls.half_len / kRowPairs) * std::uint64_t(ls.lines),
                                             std::uint32_t(g_.cfg.sensors * g_.cfg.frames)},
                        taps_);
    }

    // A row pass at `level` (region-aware), or a column pass (level -1).
    void forward(const PlaneView& src, const PlaneView& dst, const LineSpec& ls, std::uint32_t planes, int level) {
        // Rows of whole quads: eight pairs per invocation, plane4 loads and stores.
        const bool rows4 = periodization_ && ls.along_rows && ls.half_len % kRowPairs == 0 && src.row_stride % 4 == 0 &&
                           src.plane_stride % 4 == 0 && dst.row_stride % 4 == 0 && dst.plane_stride % 4 == 0;
        const Region r = level >= 0 && periodization_ ? region(SparsePass::ForwardRows, level, rows4 ? kRowPairs : kConvBlock)
                                                      : Region{};
        if (rows4) {
            const DeviceSpan in = g_.span(src.addr);
            g_.rec.dispatch("dwt_rows4", {in, in, g_.span(dst.addr), r.or_else(in)},
                            PushConstants()
                                .i32("n", ls.n)
                                .i32("half_len", ls.half_len)
                                .i32("lines", ls.lines)
                                .i32("src_row_stride", src.row_stride)
                                .u32("src_plane_stride", src.plane_stride)
                                .i32("dst_row_stride", dst.row_stride)
                                .u32("dst_plane_stride", dst.plane_stride)
                                .u32("region", r.push)
                                .u32("slot_planes", planes / std::uint32_t(g_.cfg.sensors)),
                            Recorder::LinearWork{std::uint64_t(ls.half_len / kRowPairs) * std::uint64_t(ls.lines), planes},
                            taps_);
            return;
        }
        dispatch_line("dwt_forward", "lift_forward", src, dst, ls, planes, r);
    }
    void inverse(const PlaneView& src, const PlaneView& dst, const LineSpec& ls, const Region& r) {
        dispatch_line("dwt_inverse", "lift_inverse", src, dst, ls, g_.planes_out(), r);
    }

    // Periodization: the column pass and the fusion in one kernel; of each
    // frame's block only the approximation the next level needs is written.
    void fuse_columns(const PlaneView& rows, const PlaneView& coeffs, const PlaneView& out, const LevelShape& s,
                      int level, bool deepest) {
        const Region r = region(SparsePass::ForwardCols, level, kConvBlock);
        const DeviceSpan src = g_.span(rows.addr);
        std::vector<std::uint32_t> constants = taps_;  // then the kernel's own: FRAMES
        constants.push_back(std::uint32_t(g_.cfg.frames));
        const PushConstants scalars = PushConstants()
                                          .i32("n", s.h)
                                          .i32("half_len", s.ch)
                                          .i32("columns", s.bw)
                                          .i32("row_stride", s.bw)
                                          .u32("src_plane_stride", rows.plane_stride)
                                          .u32("block_plane_stride", coeffs.plane_stride)
                                          .i32("approx_w", s.cw)
                                          .u32("channels", std::uint32_t(g_.cfg.channels))
                                          .u32("base_rule", rule_code(spec_.base_rule))
                                          .u32("detail_rule", rule_code(spec_.detail_rule))
                                          .u32("deepest", deepest ? 1 : 0);
        const std::uint32_t blocks = groups(std::uint32_t(s.ch), kConvBlock);
        // Four columns per invocation (plane4 windows) where every column is
        // computed and a quad holds only low or only high columns.
        if (r.push == 0 && s.bw % 4 == 0 && s.cw % 4 == 0) {
            g_.rec.dispatch("dwt_fuse_columns4", {src, g_.span(coeffs.addr), g_.span(out.addr)}, scalars,
                            Recorder::LinearWork{std::uint64_t(s.bw / 4) * blocks, g_.planes_out()}, constants);
            return;
        }
        g_.rec.dispatch("dwt_fuse_columns", {src, g_.span(coeffs.addr), g_.span(out.addr), r.or_else(src)},
                        PushConstants(scalars).u32("region", r.push).u32("slot_planes", std::uint32_t(g_.cfg.channels)),
                        Recorder::LinearWork{std::uint64_t(s.bw) * blocks, g_.planes_out()}, constants);
    }

    void fuse(const PlaneView& coeffs, const PlaneView& out, const LevelShape& s, bool deepest) {
        record_rule_fuse(g_, {coeffs, out, s.bw, s.bh, deepest ? s.cw : 0,
                              deepest ? s.ch : 0});
    }
};

}  // namespace

VkDeviceAddress record_wavelet(GraphBuilder& g, FrameSource& input) { return WaveletGraph(g).record(input); }

std::vector<PlaneView> record_wavelet_decompose(GraphBuilder& g, FrameSource& input) {
    return WaveletGraph(g).decompose(input);
}

VkDeviceAddress record_wavelet_cached(GraphBuilder& g, std::span<const CachedSources> groups, std::uint32_t sources,
                                      DeviceSpan table) {
    return WaveletGraph(g).fuse_cached(groups, sources, table);
}

}  // namespace vkfuse::vk

#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "common.glsl"
#include "compensated.glsl"
#include "filter_taps.glsl"
// dwt_fuse_columns.comp four columns at a time: an invocation takes PAIRS
// coefficient pairs of columns x .. x+3 and loads its window as plane4, so a
// window costs a quarter of the scalar kernel's loads; each column's outputs
// are the same dot products, fused by the same rules, in the same order. For
// blocks whose rows are whole quads and whose low columns (approx_w) are too,
// so that a quad is all low or all high columns, and for every column (no
// tile-sparse region: a region's lines need not start on a quad).
layout(local_size_x = VKFUSE_LINE_GROUP) in;
#define BUFFERS(X) X(0, plane4_t, src4) X(1, plane4_t, approx4) X(2, plane4_t, fused4)
#include "bindings.glsl"
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int n;            // samples per column (the level's input height)
    int half_len;     // coefficients per half column
    int columns;      // block width, a multiple of 4
    int row_stride;   // of every plane here, a multiple of 4
    uint src_plane_stride;
    uint block_plane_stride;  // of approx and fused
    int approx_w;     // columns [0, approx_w) hold the row pass's low half; a multiple of 4
    uint channels;
    uint base_rule;
    uint detail_rule;
    uint deepest;     // 1: the approximation takes the base rule and is not kept
} pc;
layout(constant_id = VKFUSE_FILTER_CONSTANTS) const uint FRAMES = 1u;  // as dwt_fuse_columns.comp

// Coefficient pairs per invocation: twice filter_taps.glsl's BLOCK, so that
// a window of 2 PAIRS + F - 2 rows serves 2 PAIRS outputs (1.5 loads an
// output at F = 10 instead of 2).
const int PAIRS = VKFUSE_COLUMN_PAIRS;
const int SPAN = 2 * PAIRS + MAX_TAPS - 2;

void main() {
    // A 1-D grid of column quads x blocks, quads the faster (as sparse.glsl's line_item).
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), uint(pc.columns) / 4u);
    int x = item.x * 4, block = item.y;
    uint z = gl_WorkGroupID.z;  // s * C + c
    if (block >= (pc.half_len + PAIRS - 1) / PAIRS) return;
    int o0 = block * PAIRS;
    uint s = z / pc.channels, c = z % pc.channels;
    bool low_columns = x < pc.approx_w;
    bool keep_approx = low_columns && pc.deepest == 0u;
    uint low_rule = (low_columns && pc.deepest != 0u) ? pc.base_rule : pc.detail_rule;
    vec4 low_pick[PAIRS], low_sum[PAIRS], high_pick[PAIRS], high_sum[PAIRS];
    for (uint k = 0u; k < FRAMES; ++k) {
        uint plane = (s * FRAMES + k) * pc.channels + c;
        uint column = plane * pc.src_plane_stride + uint(x);
        vec4 win[SPAN];
        [[unroll]] for (int i = 0; i < 2 * PAIRS + F - 2; ++i)
            win[i] = vec4(BUF(src4).v[(column + uint(window_sample(o0, i, pc.half_len, pc.n) * pc.row_stride)) / 4u]);
        [[unroll]] for (int b = 0; b < PAIRS; ++b) {
            vec4 lo, hi;
            [[unroll]] for (int q = 0; q < 4; ++q) {  // filter_taps.glsl's analyse(), on this window
                Dot2 l = dot2_of(0.0), h = dot2_of(0.0);
                [[unroll]] for (int j = 0; j < F; ++j) {
                    TAP_ADD(l, dec_lo(j), win[2 * b + F - 1 - j][q]);
                    TAP_ADD(h, dec_hi(j), win[2 * b + F - 1 - j][q]);
                }
                lo[q] = dot2_result(l);
                hi[q] = dot2_result(h);
            }
            rule_add4(low_rule, low_pick[b], low_sum[b], k, lo);
            rule_add4(pc.detail_rule, high_pick[b], high_sum[b], k, hi);
            int o = o0 + b;
            if (keep_approx && o < pc.half_len)
                BUF(approx4).v[(plane * pc.block_plane_stride + uint(o * pc.row_stride + x)) / 4u] = TO_PLANE4(lo);
        }
    }
    [[unroll]] for (int b = 0; b < PAIRS; ++b) {
        int o = o0 + b;
        if (o >= pc.half_len) break;
        uint at = (z * pc.block_plane_stride + uint(o * pc.row_stride + x)) / 4u;
        BUF(fused4).v[at] = TO_PLANE4(rule_result4(low_rule, FRAMES, low_pick[b], low_sum[b]));
        BUF(fused4).v[at + uint(pc.half_len * pc.row_stride) / 4u] =
            TO_PLANE4(rule_result4(pc.detail_rule, FRAMES, high_pick[b], high_sum[b]));
    }
}

#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "common.glsl"
#include "compensated.glsl"
#include "filter_taps.glsl"
// dwt_fuse_columns.comp four columns at a time: an invocation takes BLOCK
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

void main() {
    // A 1-D grid of column quads x blocks, quads the faster (as sparse.glsl's line_item).
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), uint(pc.columns) / 4u);
    int x = item.x * 4, block = item.y;
    uint z = gl_WorkGroupID.z;  // s * C + c
    if (block >= (pc.half_len + BLOCK - 1) / BLOCK) return;
    int o0 = block * BLOCK;
    uint s = z / pc.channels, c = z % pc.channels;
    bool low_columns = x < pc.approx_w;
    bool keep_approx = low_columns && pc.deepest == 0u;
    uint low_rule = (low_columns && pc.deepest != 0u) ? pc.base_rule : pc.detail_rule;
    vec4 low_pick[BLOCK], low_sum[BLOCK], high_pick[BLOCK], high_sum[BLOCK];
    for (uint k = 0u; k < FRAMES; ++k) {
        uint plane = (s * FRAMES + k) * pc.channels + c;
        uint column = plane * pc.src_plane_stride + uint(x);
        vec4 win[WINDOW];
        [[unroll]] for (int i = 0; i < 2 * BLOCK + F - 2; ++i)
            win[i] = vec4(BUF(src4).v[(column + uint(window_sample(o0, i, pc.half_len, pc.n) * pc.row_stride)) / 4u]);
        [[unroll]] for (int b = 0; b < BLOCK; ++b) {
            vec4 lo, hi;
            [[unroll]] for (int q = 0; q < 4; ++q) {
                float w[WINDOW];
                [[unroll]] for (int i = 0; i < 2 * BLOCK + F - 2; ++i) w[i] = win[i][q];
                vec2 lo_hi = analyse(w, b);
                lo[q] = lo_hi.x;
                hi[q] = lo_hi.y;
            }
            rule_add4(low_rule, low_pick[b], low_sum[b], k, lo);
            rule_add4(pc.detail_rule, high_pick[b], high_sum[b], k, hi);
            int o = o0 + b;
            if (keep_approx && o < pc.half_len)
                BUF(approx4).v[(plane * pc.block_plane_stride + uint(o * pc.row_stride + x)) / 4u] = TO_PLANE4(lo);
        }
    }
    [[unroll]] for (int b = 0; b < BLOCK; ++b) {
        int o = o0 + b;
        if (o >= pc.half_len) break;
        uint at = (z * pc.block_plane_stride + uint(o * pc.row_stride + x)) / 4u;
        BUF(fused4).v[at] = TO_PLANE4(rule_result4(low_rule, FRAMES, low_pick[b], low_sum[b]));
        BUF(fused4).v[at + uint(pc.half_len * pc.row_stride) / 4u] =
            TO_PLANE4(rule_result4(pc.detail_rule, FRAMES, high_pick[b], high_sum[b]));
    }
}

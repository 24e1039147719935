#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// One Laplacian level fused and collapsed in one pass, eight columns at a
// time, for levels whose width is a multiple of 8:
//     R_l = rule_k(G_l^k - pyrUp(G_{l+1}^k)) + pyrUp(R_{l+1})
// An invocation takes the 2 x 8 outputs of coarse samples j .. j+3 of each of
// its rows (pyr_up4.glsl), reads G_l as four plane4 per frame and row, and
// stores R_l's four. The fused detail C_l lives in registers only: storing it
// for a separate collapse pass to read back and overwrite costs two plane
// accesses per sample and a dispatch per level.
//
// coarse: G_{l+1} of every frame (cw x ch); src4: G_l of every frame; residual:
// R_{l+1} of every fused plane, complete before this pass (the levels run from
// the top down); dst4: R_l.
#define BUFFERS(X) X(0, plane4_t, src4) X(1, plane_t, coarse) X(2, plane4_t, coarse4) X(3, plane_t, residual) \
    X(4, plane4_t, residual4) X(5, plane4_t, dst4) X(6, uint, table)
#include "bindings.glsl"
layout(local_size_x = VKFUSE_LINE_GROUP) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int width;
    int height;
    int cw;
    int ch;
    uint frames;
    uint channels;
    uint use_table;
    uint group_first;  // the fused sensors covered: group_sensor() (common.glsl)
    uint group_count;
    uint group_period;
} pc;
// The detail rule (kernel_codes.h), fixed per pipeline: as a push constant
// every rule's branch would run on a SIMD device.
layout(constant_id = 0) const uint RULE = VKFUSE_RULE_MAX_ABS;
#include "pyr_up4.glsl"
PYR_UP_ROW(up_row, coarse, coarse4)
PYR_UP_ROW(up_residual_row, residual, residual4)

// Coarse rows per invocation: walking down a frame's rows, each coarse row's
// horizontal sums are loaded once and kept for the next rows' outputs, instead
// of loaded for each of the three rows that read them. Two rows measured
// fastest on lavapipe: at four, the kept rule states spill.
const int ROWS = VKFUSE_LAP_FUSE_ROWS;

void main() {
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), uint(pc.cw) / 4u);  // cw: whole quads
    int j = item.x * 4, i0 = item.y * ROWS;
    if (j >= pc.cw || i0 >= pc.ch) return;
    uint c = gl_WorkGroupID.z % pc.channels;
    uint s = group_sensor(gl_WorkGroupID.z / pc.channels, pc.group_first, pc.group_count, pc.group_period);
    uint z = s * pc.channels + c;  // the fused plane
    uint plane_size = uint(pc.width * pc.height);
    uint row4 = uint(pc.width) / 4u;
    // Quads of coarse row i0 + r's outputs: row 2i columns 2j.., 2j+4..; row 2i+1 the same.
    uint q0 = uint(2 * i0 * pc.width + 2 * j) / 4u;
    vec4 pick[4 * ROWS], sum[4 * ROWS];
    for (uint k = 0u; k < pc.frames; ++k) {
        uint frame = s * pc.frames + k;
        if (pc.use_table != 0u) frame = BUF(table).v[frame];
        uint plane = frame * pc.channels + c;
        uint base = plane * uint(pc.cw * pc.ch);
        uint g = plane * plane_size / 4u + q0;
        UpRow above = up_row(base, up_row_above(i0), j), at = up_row(base, i0, j);
        for (int r = 0; r < ROWS; ++r) {
            int i = i0 + r;
            if (i >= pc.ch) break;
            UpRow below = up_row(base, up_row_below(i), j);
            Up4 up = pyr_up_rows(above, at, below);
            uint o = 4 * r, q = g + uint(2 * r) * row4;
            rule_add4(RULE, pick[o], sum[o], k, vec4(BUF(src4).v[q]) - interleave_lo(up.even0, up.odd0));
            rule_add4(RULE, pick[o + 1], sum[o + 1], k, vec4(BUF(src4).v[q + 1u]) - interleave_hi(up.even0, up.odd0));
            if (2 * i + 1 < pc.height) {
                rule_add4(RULE, pick[o + 2], sum[o + 2], k, vec4(BUF(src4).v[q + row4]) - interleave_lo(up.even1, up.odd1));
                rule_add4(RULE, pick[o + 3], sum[o + 3], k,
                          vec4(BUF(src4).v[q + row4 + 1u]) - interleave_hi(up.even1, up.odd1));
            }
            above = at;
            at = below;
        }
    }
    // The collapse: the same walk down R_{l+1}'s rows, each output the fused
    // detail plus pyrUp(R_{l+1}) (lap_collapse.comp's sum, in its order).
    uint base = z * uint(pc.cw * pc.ch);
    uint d = z * plane_size / 4u + q0;
    UpRow above = up_residual_row(base, up_row_above(i0), j), at = up_residual_row(base, i0, j);
    for (int r = 0; r < ROWS; ++r) {
        int i = i0 + r;
        if (i >= pc.ch) break;
        UpRow below = up_residual_row(base, up_row_below(i), j);
        Up4 up = pyr_up_rows(above, at, below);
        uint o = 4 * r, q = d + uint(2 * r) * row4;
        BUF(dst4).v[q] = TO_PLANE4(interleave_lo(up.even0, up.odd0) + rule_result4(RULE, pc.frames, pick[o], sum[o]));
        BUF(dst4).v[q + 1u] =
            TO_PLANE4(interleave_hi(up.even0, up.odd0) + rule_result4(RULE, pc.frames, pick[o + 1], sum[o + 1]));
        if (2 * i + 1 < pc.height) {
            BUF(dst4).v[q + row4] =
                TO_PLANE4(interleave_lo(up.even1, up.odd1) + rule_result4(RULE, pc.frames, pick[o + 2], sum[o + 2]));
            BUF(dst4).v[q + row4 + 1u] =
                TO_PLANE4(interleave_hi(up.even1, up.odd1) + rule_result4(RULE, pc.frames, pick[o + 3], sum[o + 3]));
        }
        above = at;
        at = below;
    }
}

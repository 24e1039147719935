#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "common.glsl"
#include "compensated.glsl"
#include "filter_taps.glsl"
// The column pass of one periodization DWT level (as dwt_forward.comp) and the
// fusion of that level's coefficients across the K frames (as rule_fuse.comp)
// in one kernel. An invocation takes BLOCK coefficient pairs of one column of
// one (sensor, channel) plane: for each frame in turn it transforms its column
// window in registers and feeds the 2 BLOCK coefficients to the rule. Only the
// fused block is stored, plus what the next level reads: each frame's
// approximation (low rows of the low columns). Against a column pass then a
// fusion pass, K planes of coefficients are neither written nor read back.
layout(local_size_x = VKFUSE_LINE_GROUP) in;
// src: the row pass's output, plane (s*K + k)*C + c; approx: each frame's
// coefficient block, of which only the approximation is written; fused: the
// fused block, plane s*C + c.
#define BUFFERS(X) X(0, plane_t, src) X(1, plane_t, approx) X(2, plane_t, fused) X(3, uint, regions)
#include "bindings.glsl"
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int n;            // samples per column (the level's input height)
    int half_len;     // coefficients per half column (periodization: high half as long)
    int columns;      // block width
    int row_stride;   // of every plane here
    uint src_plane_stride;
    uint block_plane_stride;  // of approx and fused
    int approx_w;     // columns [0, approx_w) hold the row pass's low half
    uint channels;
    uint base_rule;
    uint detail_rule;
    uint deepest;     // 1: the approximation takes the base rule and is not kept
    uint region;      // sparse.glsl: lines are columns, in a low and a high half
    uint slot_planes; // channels
} pc;
#include "sparse.glsl"
// K, after filter_taps.glsl's constants: the loop over the frames unrolls, and
// each frame's rule state stays in registers (on lavapipe a value updated in a
// loop of unknown length lives in memory, under a mask).
layout(constant_id = VKFUSE_FILTER_CONSTANTS) const uint FRAMES = 1u;

void main() {
    int x, block;
    uint z = gl_WorkGroupID.z;  // s * C + c
    if (!line_item(z, true, pc.columns, (pc.half_len + BLOCK - 1) / BLOCK, x, block)) return;
    int o0 = block * BLOCK;
    uint s = z / pc.channels, c = z % pc.channels;
    bool low_columns = x < pc.approx_w;
    bool keep_approx = low_columns && pc.deepest == 0u;
    uint low_rule = (low_columns && pc.deepest != 0u) ? pc.base_rule : pc.detail_rule;
    RuleState low[BLOCK], high[BLOCK];
    for (uint k = 0u; k < FRAMES; ++k) {
        uint plane = (s * FRAMES + k) * pc.channels + c;
        uint column = plane * pc.src_plane_stride + uint(x);
        float win[WINDOW];
        [[unroll]] for (int i = 0; i < 2 * BLOCK + F - 2; ++i)
            win[i] = BUF(src).v[column + uint(window_sample(o0, i, pc.half_len, pc.n) * pc.row_stride)];
        [[unroll]] for (int b = 0; b < BLOCK; ++b) {
            vec2 lo_hi = analyse(win, b);
            rule_add(low[b], low_rule, k, lo_hi.x);
            rule_add(high[b], pc.detail_rule, k, lo_hi.y);
            int o = o0 + b;
            if (keep_approx && o < pc.half_len)
                BUF(approx).v[plane * pc.block_plane_stride + uint(o * pc.row_stride + x)] = TO_PLANE(lo_hi.x);
        }
    }
    [[unroll]] for (int b = 0; b < BLOCK; ++b) {
        int o = o0 + b;
        if (o >= pc.half_len) break;
        uint at = z * pc.block_plane_stride + uint(o * pc.row_stride + x);
        BUF(fused).v[at] = TO_PLANE(rule_result(low[b], low_rule, FRAMES));
        BUF(fused).v[at + uint(pc.half_len * pc.row_stride)] = TO_PLANE(rule_result(high[b], pc.detail_rule, FRAMES));
    }
}

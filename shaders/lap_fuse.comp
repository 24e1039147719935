#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Fusion of one Laplacian level below the top: the coefficient of frame k is
// G_l - pyrUp(G_{l+1}), formed here and never stored, and the detail rule
// picks across the K frames. An invocation takes the 2 x 2 outputs that share
// one 3 x 3 neighbourhood of G_{l+1} (pyr_up_block). Source planes are
// (s*K + k)*C + c, the fused plane (s, c) is s*C + c; with use_table, frame
// k of sensor s is source frame table[s*K + k] instead (rule_fuse.comp).
layout(local_size_x = VKFUSE_LINE_GROUP) in;
// src: G_l planes, width x height; coarse: G_{l+1} planes, cw x ch; dst: the
// fused planes, width x height.
#define BUFFERS(X) X(0, plane_t, src) X(1, plane_t, coarse) X(2, plane_t, dst) X(3, uint, table)
#include "bindings.glsl"
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
#include "pyr_up.glsl"

void main() {
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), uint(pc.cw));
    int j = item.x, i = item.y;
    if (j >= pc.cw || i >= pc.ch) return;
    uint c = gl_WorkGroupID.z % pc.channels;
    uint s = group_sensor(gl_WorkGroupID.z / pc.channels, pc.group_first, pc.group_count, pc.group_period);
    uint z = s * pc.channels + c;  // the fused plane
    uint plane_size = uint(pc.width * pc.height);
    RuleState st[4];
    for (uint k = 0u; k < pc.frames; ++k) {
        uint frame = s * pc.frames + k;
        if (pc.use_table != 0u) frame = BUF(table).v[frame];
        uint plane = frame * pc.channels + c;
        mat2 up = pyr_up_block(plane * uint(pc.cw * pc.ch), pc.cw, pc.ch, i, j);
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) {
                int y = 2 * i + a, x = 2 * j + b;
                if (y < pc.height && x < pc.width)
                    rule_add(st[2 * a + b], RULE, k, BUF(src).v[plane * plane_size + uint(y * pc.width + x)] - up[a][b]);
            }
    }
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            int y = 2 * i + a, x = 2 * j + b;
            if (y < pc.height && x < pc.width)
                BUF(dst).v[z * plane_size + uint(y * pc.width + x)] = TO_PLANE(rule_result(st[2 * a + b], RULE, pc.frames));
        }
}

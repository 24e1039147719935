#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// lap_fuse.comp eight columns at a time, for levels whose width is a multiple
// of 8: an invocation takes the 2 x 8 outputs of coarse samples j .. j+3 of
// row i (pyr_up4.glsl), reads G_l as four plane4 per frame and stores four.
#define BUFFERS(X) X(0, plane4_t, src4) X(1, plane_t, coarse) X(2, plane4_t, coarse4) X(3, plane4_t, dst4) \
    X(4, uint, table)
#include "bindings.glsl"
layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int width;
    int height;
    int cw;
    int ch;
    uint frames;
    uint channels;
    uint rule;
    uint use_table;
    uint group_first;  // the fused sensors covered: group_sensor() (common.glsl)
    uint group_count;
    uint group_period;
} pc;
#include "pyr_up4.glsl"

void main() {
    int j = int(gl_GlobalInvocationID.x) * 4, i = int(gl_GlobalInvocationID.y);
    if (j >= pc.cw || i >= pc.ch) return;
    uint c = gl_WorkGroupID.z % pc.channels;
    uint s = group_sensor(gl_WorkGroupID.z / pc.channels, pc.group_first, pc.group_count, pc.group_period);
    uint z = s * pc.channels + c;  // the fused plane
    uint plane_size = uint(pc.width * pc.height);
    bool second_row = 2 * i + 1 < pc.height;
    // Quads of the outputs: row 2i columns 2j.., 2j+4..; row 2i+1 the same.
    uint q0 = uint(2 * i * pc.width + 2 * j) / 4u, q2 = q0 + uint(pc.width) / 4u;
    vec4 pick[4], sum[4];
    for (uint k = 0u; k < pc.frames; ++k) {
        uint frame = s * pc.frames + k;
        if (pc.use_table != 0u) frame = BUF(table).v[frame];
        uint plane = frame * pc.channels + c;
        Up4 up = pyr_up_quad(plane * uint(pc.cw * pc.ch), i, j);
        uint g = plane * plane_size / 4u;
        rule_add4(pc.rule, pick[0], sum[0], k, vec4(BUF(src4).v[g + q0]) - interleave_lo(up.even0, up.odd0));
        rule_add4(pc.rule, pick[1], sum[1], k, vec4(BUF(src4).v[g + q0 + 1u]) - interleave_hi(up.even0, up.odd0));
        if (second_row) {
            rule_add4(pc.rule, pick[2], sum[2], k, vec4(BUF(src4).v[g + q2]) - interleave_lo(up.even1, up.odd1));
            rule_add4(pc.rule, pick[3], sum[3], k, vec4(BUF(src4).v[g + q2 + 1u]) - interleave_hi(up.even1, up.odd1));
        }
    }
    uint d = z * plane_size / 4u;
    BUF(dst4).v[d + q0] = TO_PLANE4(rule_result4(pc.rule, pc.frames, pick[0], sum[0]));
    BUF(dst4).v[d + q0 + 1u] = TO_PLANE4(rule_result4(pc.rule, pc.frames, pick[1], sum[1]));
    if (second_row) {
        BUF(dst4).v[d + q2] = TO_PLANE4(rule_result4(pc.rule, pc.frames, pick[2], sum[2]));
        BUF(dst4).v[d + q2 + 1u] = TO_PLANE4(rule_result4(pc.rule, pc.frames, pick[3], sum[3]));
    }
}

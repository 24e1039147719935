#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// lap_collapse.comp eight columns at a time, for levels whose width is a
// multiple of 8: C_l += pyrUp(R_{l+1}) over the 2 x 8 outputs of coarse
// samples j .. j+3 of row i (pyr_up4.glsl), in place.
#define BUFFERS(X) X(0, plane_t, coarse) X(1, plane4_t, coarse4) X(2, plane4_t, fine4)
#include "bindings.glsl"
layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int width;
    int height;
    int cw;
    int ch;
} pc;
#include "pyr_up4.glsl"

void main() {
    int j = int(gl_GlobalInvocationID.x) * 4, i = int(gl_GlobalInvocationID.y);
    uint z = gl_WorkGroupID.z;
    if (j >= pc.cw || i >= pc.ch) return;
    Up4 up = pyr_up_quad(z * uint(pc.cw * pc.ch), i, j);
    uint q0 = (z * uint(pc.width * pc.height) + uint(2 * i * pc.width + 2 * j)) / 4u;
    BUF(fine4).v[q0] = TO_PLANE4(interleave_lo(up.even0, up.odd0) + vec4(BUF(fine4).v[q0]));
    BUF(fine4).v[q0 + 1u] = TO_PLANE4(interleave_hi(up.even0, up.odd0) + vec4(BUF(fine4).v[q0 + 1u]));
    if (2 * i + 1 >= pc.height) return;
    uint q2 = q0 + uint(pc.width) / 4u;
    BUF(fine4).v[q2] = TO_PLANE4(interleave_lo(up.even1, up.odd1) + vec4(BUF(fine4).v[q2]));
    BUF(fine4).v[q2 + 1u] = TO_PLANE4(interleave_hi(up.even1, up.odd1) + vec4(BUF(fine4).v[q2 + 1u]));
}

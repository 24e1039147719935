#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// lap_collapse.comp eight columns at a time, for levels whose width is a
// multiple of 8: C_l += pyrUp(R_{l+1}) over the 2 x 8 outputs of coarse
// samples j .. j+3 of each of its rows (pyr_up4.glsl), in place.
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

// Coarse rows per invocation, as lap_fuse4.comp: each coarse row's horizontal
// sums loaded once for the output rows they feed. With no rule state to keep,
// four rows measured faster than two on lavapipe.
const int ROWS = VKFUSE_LAP_COLLAPSE_ROWS;

void main() {
    int j = int(gl_GlobalInvocationID.x) * 4, i0 = int(gl_GlobalInvocationID.y) * ROWS;
    uint z = gl_WorkGroupID.z;
    if (j >= pc.cw || i0 >= pc.ch) return;
    uint base = z * uint(pc.cw * pc.ch);
    uint row4 = uint(pc.width) / 4u;
    uint q0 = (z * uint(pc.width * pc.height) + uint(2 * i0 * pc.width + 2 * j)) / 4u;
    UpRow above = up_row(base, up_row_above(i0), j), at = up_row(base, i0, j);
    for (int r = 0; r < ROWS; ++r) {
        int i = i0 + r;
        if (i >= pc.ch) return;
        UpRow below = up_row(base, up_row_below(i), j);
        Up4 up = pyr_up_rows(above, at, below);
        uint q = q0 + uint(2 * r) * row4;
        BUF(fine4).v[q] = TO_PLANE4(interleave_lo(up.even0, up.odd0) + vec4(BUF(fine4).v[q]));
        BUF(fine4).v[q + 1u] = TO_PLANE4(interleave_hi(up.even0, up.odd0) + vec4(BUF(fine4).v[q + 1u]));
        if (2 * i + 1 >= pc.height) return;
        BUF(fine4).v[q + row4] = TO_PLANE4(interleave_lo(up.even1, up.odd1) + vec4(BUF(fine4).v[q + row4]));
        BUF(fine4).v[q + row4 + 1u] = TO_PLANE4(interleave_hi(up.even1, up.odd1) + vec4(BUF(fine4).v[q + row4 + 1u]));
        above = at;
        at = below;
    }
}

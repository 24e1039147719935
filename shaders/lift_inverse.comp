#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "compensated.glsl"
#include "line.glsl"
#define LIFT_COEF src  // undone in place in the input
#include "lifting.glsl"
// Inverse symmetric-mode DWT, one line per invocation: undo the scaling and
// the steps in reverse order in place in the coefficient line (src, which the
// plan rewrites every cycle), then write the line in natural order to dst.
layout(local_size_x = 64) in;

void main() {
    uint plane = gl_WorkGroupID.z;
    int line = int(gl_GlobalInvocationID.x);
    if (line >= pc.lines) return;
    int n = pc.n;
    LineView coef_view = LineView(pc.src_plane_stride, pc.src_line_stride, pc.src_elem_stride);
    if (n > 1) {
        lift_scale(coef_view, plane, line, n, false);
        int steps = int(BUF(scheme).v[0]);
        for (int s = steps - 1; s >= 0; --s) lift_step(coef_view, plane, line, n, s, -1.0);
    }
    for (int p = 0; p < n; ++p) BUF(dst).v[dst_at(plane, line, p)] = BUF(src).v[lift_slot(coef_view, plane, line, p)];
}

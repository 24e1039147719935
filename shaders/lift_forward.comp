#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "compensated.glsl"
#include "line.glsl"
#define LIFT_COEF dst  // lifted in place in the output
#include "lifting.glsl"
// Forward symmetric-mode DWT, one line per invocation: copy src into split
// layout in dst, apply the lifting steps in order, scale. A length-1 line is
// copied unscaled.
layout(local_size_x = 64) in;

void main() {
    uint plane = gl_WorkGroupID.z;
    int line = int(gl_GlobalInvocationID.x);
    if (line >= pc.lines) return;
    int n = pc.n;
    LineView out_view = LineView(pc.dst_plane_stride, pc.dst_line_stride, pc.dst_elem_stride);
    for (int p = 0; p < n; ++p) BUF(dst).v[lift_slot(out_view, plane, line, p)] = BUF(src).v[src_at(plane, line, p)];
    if (n == 1) return;
    int steps = int(BUF(scheme).v[0]);
    for (int s = 0; s < steps; ++s) lift_step(out_view, plane, line, n, s, 1.0);
    lift_scale(out_view, plane, line, n, true);
}

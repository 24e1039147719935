#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Planar fused planes (s*C + c) -> interleaved HWC float per sensor (workgroup
// z = s), written straight into host-visible memory: the only copy of the
// image the host reads. Where a plane holds a multiple of 4 pixels, each
// invocation packs 4 pixels: one plane4 per channel in, C vec4 out.
#define BUFFERS(X) X(0, plane_t, src) X(1, plane4_t, src4) X(2, float, dst) X(3, vec4, dst4)
#include "bindings.glsl"
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint pixels;
    uint channels;
    uint quads;  // pixels % 4 == 0
} pc;

void main() {
    uint i = linear_index(256u), s = gl_WorkGroupID.z, C = pc.channels;
    if (pc.quads == 0u) {
        if (i >= pc.pixels) return;
        for (uint c = 0u; c < C; ++c)
            BUF(dst).v[(s * pc.pixels + i) * C + c] = float(BUF(src).v[(s * C + c) * pc.pixels + i]);
        return;
    }
    if (i >= pc.pixels / 4u) return;
    float o[12];
    for (uint c = 0u; c < C; ++c) {
        vec4 q = vec4(BUF(src4).v[((s * C + c) * pc.pixels) / 4u + i]);
        for (uint p = 0u; p < 4u; ++p) o[p * C + c] = q[p];
    }
    uint first = (s * pc.pixels / 4u + i) * C;  // vec4 index of pixel 4i's first sample
    for (uint w = 0u; w < C; ++w) BUF(dst4).v[first + w] = vec4(o[4u * w], o[4u * w + 1u], o[4u * w + 2u], o[4u * w + 3u]);
}

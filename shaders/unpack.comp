#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Interleaved HWC frames (uint8 or float32, as the camera or file gave them)
// -> planar planes, frame f channel c at plane f * C + c (workgroup z = f).
// Where a plane holds a multiple of 4 pixels (`quads`), each invocation
// converts 4 pixels: C words of 8-bit input or C vec4 of float input in,
// one plane4 per channel out. Otherwise one pixel per invocation.
#define BUFFERS(X) X(0, uint, frame_words) X(1, vec4, frame_quads) X(2, plane_t, dst) X(3, plane4_t, dst4)
#include "bindings.glsl"
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint pixels;    // width * height: the plane stride
    uint channels;  // 1 or 3
    uint is_u8;
    uint quads;     // pixels % 4 == 0: 4 pixels per invocation
} pc;
#define VKFUSE_READS_FRAMES
#include "frames.glsl"

void main() {
    uint i = linear_index(256u), f = gl_WorkGroupID.z, C = pc.channels;
    if (pc.quads == 0u) {
        if (i >= pc.pixels) return;
        for (uint c = 0u; c < C; ++c) BUF(dst).v[(f * C + c) * pc.pixels + i] = TO_PLANE(frame_sample(f, i, c));
        return;
    }
    if (i >= pc.pixels / 4u) return;
    Quad q = frame_quad(f, i);
    uint out0 = (f * C * pc.pixels) / 4u + i, stride = pc.pixels / 4u;
    BUF(dst4).v[out0] = TO_PLANE4(q.c0);
    if (C == 1u) return;
    BUF(dst4).v[out0 + stride] = TO_PLANE4(q.c1);
    BUF(dst4).v[out0 + 2u * stride] = TO_PLANE4(q.c2);
}

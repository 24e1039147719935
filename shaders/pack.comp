#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Planar fused planes (s*C + c) -> interleaved HWC float per sensor (workgroup
// z = s), written straight into host-visible memory: the only copy of the
// image the host reads. Where a plane holds a multiple of 4 pixels, each
// invocation packs 4 pixels: one plane4 per channel in, C vec4 out.
#define BUFFERS(X) X(0, plane_t, src) X(1, plane4_t, src4) X(2, float, image) X(3, vec4, image_quads)
#include "bindings.glsl"
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint pixels;
    uint channels;
    uint quads;  // pixels % 4 == 0
} pc;
#define VKFUSE_WRITES_IMAGES
#include "frames.glsl"

void main() {
    uint i = linear_index(256u), s = gl_WorkGroupID.z, C = pc.channels;
    if (pc.quads == 0u) {
        if (i >= pc.pixels) return;
        for (uint c = 0u; c < C; ++c) store_image_sample(s, i, c, float(BUF(src).v[(s * C + c) * pc.pixels + i]));
        return;
    }
    if (i >= pc.pixels / 4u) return;
    uint in0 = (s * C * pc.pixels) / 4u + i, stride = pc.pixels / 4u;
    vec4 r = vec4(BUF(src4).v[in0]);
    Quad q = C == 1u ? Quad(r, r, r) : Quad(r, vec4(BUF(src4).v[in0 + stride]), vec4(BUF(src4).v[in0 + 2u * stride]));
    store_image_quad(s, i, q);
}

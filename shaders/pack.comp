#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Planar fused planes (s*C + c) -> interleaved HWC float per sensor, written
// straight into host-visible memory: the only copy of the image the host reads.
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    Planes src;
    Floats dst;
    uint pixels;
    uint channels;
} pc;

void main() {
    uint p = linear_index(256u), s = gl_WorkGroupID.z;
    if (p >= pc.pixels) return;
    for (uint c = 0u; c < pc.channels; ++c)
        pc.dst.v[(s * pc.pixels + p) * pc.channels + c] = pc.src.v[(s * pc.channels + c) * pc.pixels + p];
}

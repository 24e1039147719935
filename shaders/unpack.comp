#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Interleaved HWC frames (uint8 or float32, as the camera or file gave them)
// -> planar float32 planes, frame f channel c at plane f * C + c.
layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, std430) uniform Push {
    Words src;
    Planes dst;
    uint width;
    uint height;
    uint channels;
    uint is_u8;
    uint frame_elems;   // width * height * channels
    uint plane_stride;  // width * height
} pc;

void main() {
    uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y, f = gl_WorkGroupID.z;
    if (x >= pc.width || y >= pc.height) return;
    uint pix = y * pc.width + x;
    for (uint c = 0u; c < pc.channels; ++c) {
        uint idx = f * pc.frame_elems + pix * pc.channels + c;
        float v;
        if (pc.is_u8 != 0u) {
            uint word = pc.src.v[idx >> 2u];
            v = float((word >> ((idx & 3u) * 8u)) & 255u) / 255.0;
        } else {
            v = uintBitsToFloat(pc.src.v[idx]);
        }
        pc.dst.v[(f * pc.channels + c) * pc.plane_stride + pix] = TO_PLANE(v);
    }
}

#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Interleaved HWC frames (uint8 or float32, as the camera or file gave them)
// -> planar planes, frame f channel c at plane f * C + c (workgroup z = f).
// Where a plane holds a multiple of 4 pixels (`quads`), each invocation
// converts 4 pixels: C words of 8-bit input or C vec4 of float input in,
// one plane4 per channel out, 2C accesses for 4C samples. Otherwise one
// pixel per invocation, sample by sample.
#define BUFFERS(X) X(0, uint, words) X(1, vec4, quads_in) X(2, plane_t, dst) X(3, plane4_t, dst4)
#include "bindings.glsl"
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint pixels;    // width * height: the plane stride
    uint channels;  // 1 or 3
    uint is_u8;
    uint quads;     // pixels % 4 == 0: 4 pixels per invocation
} pc;

float sample_at(uint idx) {  // sample idx of the frames as uploaded
    if (pc.is_u8 == 0u) return uintBitsToFloat(BUF(words).v[idx]);
    return float((BUF(words).v[idx >> 2u] >> ((idx & 3u) * 8u)) & 255u) / 255.0;
}

void main() {
    uint i = linear_index(256u), f = gl_WorkGroupID.z, C = pc.channels;
    if (pc.quads == 0u) {
        if (i >= pc.pixels) return;
        for (uint c = 0u; c < C; ++c)
            BUF(dst).v[(f * C + c) * pc.pixels + i] = TO_PLANE(sample_at((f * pc.pixels + i) * C + c));
        return;
    }
    if (i >= pc.pixels / 4u) return;
    // The 4C samples of pixels 4i..4i+3, interleaved: C words or C vec4.
    float s[12];
    uint first = f * pc.pixels * C / 4u + i * C;  // in words, or in vec4 of float input
    for (uint w = 0u; w < C; ++w) {
        if (pc.is_u8 != 0u) {
            uint word = BUF(words).v[first + w];
            for (uint b = 0u; b < 4u; ++b) s[w * 4u + b] = float((word >> (b * 8u)) & 255u) / 255.0;
        } else {
            vec4 q = BUF(quads_in).v[first + w];
            for (uint b = 0u; b < 4u; ++b) s[w * 4u + b] = q[b];
        }
    }
    for (uint c = 0u; c < C; ++c)
        BUF(dst4).v[((f * C + c) * pc.pixels) / 4u + i] = TO_PLANE4(vec4(s[c], s[C + c], s[2u * C + c], s[3u * C + c]));
}

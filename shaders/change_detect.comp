#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Change detection (docs/spec.md, "Skipping"; core/skip.cpp is its CPU twin):
// one workgroup per 32 x 32 tile (x, y) of sensor z. Each invocation takes 4
// neighbouring pixels of one tile row and, over the K frames of the cycle and
// every channel, the largest |frame - background mean| times the tile's
// inverse noise under that frame's setting; the group's largest is the tile's
// score. Frames are read as uploaded (frames.glsl), once; the means are
// planar float32, plane (s * K + k) * C + c, read as vec4 where planes hold
// whole quads.
#define BUFFERS(X) X(0, uint, frame_words) X(1, vec4, frame_quads) X(2, float, means) X(3, vec4, means4) \
    X(4, float, inv_noise) X(5, float, scores)
#include "bindings.glsl"
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint pixels;
    uint channels;
    uint is_u8;
    uint width;
    uint height;
    uint frames;   // K
    uint quads;    // pixels % 4 == 0 and width % 4 == 0: a 4-pixel run is one quad
} pc;
#define VKFUSE_READS_FRAMES
#include "frames.glsl"

const uint TILE = 32u;
shared float group_max[256];

float quad_deviation(vec4 v, vec4 m) {
    vec4 d = abs(v - m);
    return max(max(d.x, d.y), max(d.z, d.w));
}

void main() {
    uint s = gl_WorkGroupID.z, K = pc.frames, C = pc.channels, id = gl_LocalInvocationID.x;
    uint tiles_x = gl_NumWorkGroups.x, tile = gl_WorkGroupID.y * tiles_x + gl_WorkGroupID.x;
    uint y = gl_WorkGroupID.y * TILE + id / 8u, x = gl_WorkGroupID.x * TILE + (id % 8u) * 4u;
    float score = 0.0;
    if (y < pc.height && x < pc.width) {
        uint p = y * pc.width + x;
        for (uint k = 0u; k < K; ++k) {
            uint f = s * K + k;
            float inv = BUF(inv_noise).v[f * tiles_x * gl_NumWorkGroups.y + tile];
            float worst = 0.0;
            if (pc.quads != 0u) {
                Quad q = frame_quad(f, p / 4u);
                uint m = f * C * (pc.pixels / 4u) + p / 4u, stride = pc.pixels / 4u;
                worst = quad_deviation(q.c0, BUF(means4).v[m]);
                if (C == 3u) {
                    worst = max(worst, quad_deviation(q.c1, BUF(means4).v[m + stride]));
                    worst = max(worst, quad_deviation(q.c2, BUF(means4).v[m + 2u * stride]));
                }
            } else {
                for (uint j = 0u; j < 4u && x + j < pc.width; ++j)
                    for (uint c = 0u; c < C; ++c)
                        worst = max(worst, abs(frame_sample(f, p + j, c) - BUF(means).v[(f * C + c) * pc.pixels + p + j]));
            }
            score = max(score, worst * inv);
        }
    }
    group_max[id] = score;
    barrier();
    for (uint half_n = 128u; half_n > 0u; half_n >>= 1u) {
        if (id < half_n) group_max[id] = max(group_max[id], group_max[id + half_n]);
        barrier();
    }
    if (id == 0u) BUF(scores).v[s * tiles_x * gl_NumWorkGroups.y + tile] = group_max[0];
}

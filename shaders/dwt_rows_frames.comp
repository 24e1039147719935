#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "common.glsl"
#include "compensated.glsl"
#include "filter_taps.glsl"
// The first row pass of a periodization DWT straight from the frames as
// uploaded (HWC, 8-bit or float32; frames.glsl), so that unpacking them into
// planes is no pass of its own: an invocation computes 8 pairs of one row of
// one frame (dwt_row_pairs.glsl) for every channel, from windows loaded
// together, C words or vec4 per four pixels, as unpack.comp reads them.
// Rows of whole quads (width % 4 == 0) whose half length is a multiple of 8.
#define BUFFERS(X) X(0, uint, frame_words) X(1, vec4, frame_quads) X(2, plane4_t, dst4) X(3, uint, regions)
#include "bindings.glsl"
layout(local_size_x = VKFUSE_LINE_GROUP) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint pixels;      // width * height
    uint channels;    // 1 or 3
    uint is_u8;
    int n;            // samples per row: the width
    int half_len;     // coefficients per half (a multiple of 8)
    int lines;        // rows: the height
    int dst_row_stride;
    uint dst_plane_stride;
    uint region;       // sparse.glsl
    uint slot_planes;  // frames per sensor
} pc;
#define VKFUSE_READS_FRAMES
#include "frames.glsl"
#include "dwt_row_pairs.glsl"
#include "sparse.glsl"

void main() {
    int line, block;
    uint f = gl_WorkGroupID.z;  // frame s * K + k
    if (!line_item(f, false, pc.lines, pc.half_len / PAIRS, line, block)) return;
    int o0 = block * PAIRS;
    uint C = pc.channels, row = uint(line * pc.n);  // the row's first pixel
    int base = window_base(o0);
    float w0[WINDOW_QUADS], w1[WINDOW_QUADS], w2[WINDOW_QUADS];
    if (window_inside(base, pc.n)) {
        [[unroll]] for (int q = 0; q < QUADS; ++q) {
            Quad p = frame_quad(f, (row + uint(base)) / 4u + uint(q));
            [[unroll]] for (int t = 0; t < 4; ++t) {
                w0[4 * q + t] = p.c0[t];
                w1[4 * q + t] = p.c1[t];
                w2[4 * q + t] = p.c2[t];
            }
        }
    } else {
        [[unroll]] for (int i = 0; i < 2 * PAIRS + F - 2; ++i) {
            uint p = row + uint(window_sample(o0, i, pc.half_len, pc.n));
            w0[SHIFT + i] = frame_sample(f, p, 0u);
            w1[SHIFT + i] = C == 3u ? frame_sample(f, p, 1u) : 0.0;
            w2[SHIFT + i] = C == 3u ? frame_sample(f, p, 2u) : 0.0;
        }
    }
    store_pairs(w0, f * C, line, o0);
    if (C == 1u) return;
    store_pairs(w1, f * C + 1u, line, o0);
    store_pairs(w2, f * C + 2u, line, o0);
}

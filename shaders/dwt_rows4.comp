#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "common.glsl"
#include "compensated.glsl"
#include "filter_taps.glsl"
// dwt_forward.comp along rows, for lines whose half length is a multiple of 8
// and whose rows and planes start on a quad: an invocation computes 8
// consecutive (low, high) pairs of one row (dwt_row_pairs.glsl), its window
// read as plane4 where it lies inside the row, elsewhere sample by sample,
// periodic as dwt_forward.
#define BUFFERS(X) X(0, plane_t, src) X(1, plane4_t, src4) X(2, plane4_t, dst4) X(3, uint, regions)
#include "bindings.glsl"
layout(local_size_x = VKFUSE_LINE_GROUP) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int n;            // samples per row
    int half_len;     // coefficients per half (a multiple of 8)
    int lines;        // rows per plane
    int src_row_stride;
    uint src_plane_stride;
    int dst_row_stride;
    uint dst_plane_stride;
    uint region;       // sparse.glsl
    uint slot_planes;  // planes per sensor: K C
} pc;
#include "dwt_row_pairs.glsl"
#include "sparse.glsl"

void main() {
    int line, block;
    uint plane = gl_WorkGroupID.z;
    if (!line_item(plane, false, pc.lines, pc.half_len / PAIRS, line, block)) return;
    int o0 = block * PAIRS;
    uint row = plane * pc.src_plane_stride + uint(line * pc.src_row_stride);
    int base = window_base(o0);
    float win[WINDOW_QUADS];
    if (window_inside(base, pc.n)) {
        [[unroll]] for (int q = 0; q < QUADS; ++q) {
            vec4 v = vec4(BUF(src4).v[(row + uint(base)) / 4u + uint(q)]);
            win[4 * q] = v.x;
            win[4 * q + 1] = v.y;
            win[4 * q + 2] = v.z;
            win[4 * q + 3] = v.w;
        }
    } else {
        [[unroll]] for (int i = 0; i < 2 * PAIRS + F - 2; ++i)
            win[SHIFT + i] = float(BUF(src).v[row + uint(window_sample(o0, i, pc.half_len, pc.n))]);
    }
    store_pairs(win, plane, line, o0);
}

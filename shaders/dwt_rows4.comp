#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "common.glsl"
#include "compensated.glsl"
#include "filter_taps.glsl"
// dwt_forward.comp along rows, for lines whose half length is a multiple of 8
// and whose rows and planes start on a quad: an invocation computes 8
// consecutive (low, high) pairs from one window of 2 * 8 + F - 2 samples,
// read as plane4 where the window lies inside the row (elsewhere sample by
// sample, periodic as dwt_forward), and stores them as four plane4. Each
// output is the same compensated dot product as dwt_forward's.
#define BUFFERS(X) X(0, plane_t, src) X(1, plane4_t, src4) X(2, plane4_t, dst4)
#include "bindings.glsl"
layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int n;            // samples per row
    int half_len;     // coefficients per half (a multiple of 8)
    int lines;        // rows per plane
    int src_row_stride;
    uint src_plane_stride;
    int dst_row_stride;
    uint dst_plane_stride;
} pc;

const int PAIRS = 8;
const int SPAN = 2 * PAIRS + MAX_TAPS - 2;  // longest window
// The window starts at sample 2 o0 + 1 - F/2: SHIFT past a quad boundary.
const int SHIFT = ((1 - F / 2) % 4 + 4) % 4;
const int QUADS = (SPAN + 3 + 3) / 4;

void main() {
    int o0 = int(gl_GlobalInvocationID.x) * PAIRS, line = int(gl_GlobalInvocationID.y);
    uint plane = gl_WorkGroupID.z;
    if (o0 >= pc.half_len || line >= pc.lines) return;
    uint row = plane * pc.src_plane_stride + uint(line * pc.src_row_stride);
    int base = 2 * o0 + 1 - F / 2 - SHIFT;  // a multiple of 4
    float win[QUADS * 4];  // window sample i at win[SHIFT + i]
    if (base >= 0 && base + QUADS * 4 <= pc.n) {
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
    float lo[PAIRS], hi[PAIRS];
    [[unroll]] for (int b = 0; b < PAIRS; ++b) {
        Dot2 l = dot2_of(0.0), h = dot2_of(0.0);
        [[unroll]] for (int j = 0; j < F; ++j) {  // x[F/2 + 2o - j] is window sample 2b + F - 1 - j
            TAP_ADD(l, dec_lo(j), win[SHIFT + 2 * b + F - 1 - j]);
            TAP_ADD(h, dec_hi(j), win[SHIFT + 2 * b + F - 1 - j]);
        }
        lo[b] = dot2_result(l);
        hi[b] = dot2_result(h);
    }
    uint out_ = (plane * pc.dst_plane_stride + uint(line * pc.dst_row_stride + o0)) / 4u;
    uint high = uint(pc.half_len) / 4u;
    BUF(dst4).v[out_] = TO_PLANE4(vec4(lo[0], lo[1], lo[2], lo[3]));
    BUF(dst4).v[out_ + 1u] = TO_PLANE4(vec4(lo[4], lo[5], lo[6], lo[7]));
    BUF(dst4).v[out_ + high] = TO_PLANE4(vec4(hi[0], hi[1], hi[2], hi[3]));
    BUF(dst4).v[out_ + high + 1u] = TO_PLANE4(vec4(hi[4], hi[5], hi[6], hi[7]));
}

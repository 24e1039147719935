#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "common.glsl"
#include "compensated.glsl"
#include "line.glsl"
#include "filter_taps.glsl"
#include "sparse.glsl"
// One level of pywt's periodization DWT along a line (exactly
// downsampling_convolution_periodization): an odd line is first extended by
// repeating its last sample to even length N, then
//   low[o]  = sum_j dec_lo[j] * x[(F/2 + 2o - j) mod N]
//   high[o] = sum_j dec_hi[j] * x[(F/2 + 2o - j) mod N]
// for o < N/2; low goes to positions [0, N/2), high to [N/2, N).
// An invocation computes BLOCK consecutive (low, high) pairs from one window
// of 2 BLOCK + F - 2 samples.
layout(local_size_x = VKFUSE_LINE_GROUP) in;

void main() {
    uint plane = gl_WorkGroupID.z;
    int line, block;
    if (!line_item(plane, pc.lines_fastest != 0u, pc.lines, (pc.half_len + BLOCK - 1) / BLOCK, line, block)) return;
    int o0 = block * BLOCK;
    float win[WINDOW];
    [[unroll]] for (int i = 0; i < 2 * BLOCK + F - 2; ++i)
        win[i] = BUF(src).v[src_at(plane, line, window_sample(o0, i, pc.half_len, pc.n))];
    [[unroll]] for (int b = 0; b < BLOCK; ++b) {
        int o = o0 + b;
        if (o >= pc.half_len) break;
        vec2 lo_hi = analyse(win, b);
        BUF(dst).v[dst_at(plane, line, o)] = TO_PLANE(lo_hi.x);
        BUF(dst).v[dst_at(plane, line, pc.half_len + o)] = TO_PLANE(lo_hi.y);
    }
}

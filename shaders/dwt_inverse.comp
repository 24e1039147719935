#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "common.glsl"
#include "compensated.glsl"
#include "line.glsl"
#include "filter_taps.glsl"
#include "sparse.glsl"
// One level of pywt's periodization inverse DWT along a line (exactly
// upsampling_convolution_valid_sf_periodization for (low, rec_lo) plus
// (high, rec_hi)): with M = half_len coefficients per half, F taps, Hf = F/2,
// start = F/4 and a one-sample shift s = 1 when Hf is even (db2),
//   q = (m - s) mod 2M, o = q / 2, p = q mod 2
//   x[m] = sum_{j < Hf} rec_lo[2j + p] low[(o + start - j) mod M]
//                     + rec_hi[2j + p] high[(o + start - j) mod M]
// Only the first n of the 2M samples are written: pywt's crop for odd sizes.
// An invocation computes the 2 BLOCK samples of BLOCK consecutive o from one
// window of BLOCK + Hf - 1 coefficients of each half.
layout(local_size_x = VKFUSE_LINE_GROUP) in;

void main() {
    uint plane = gl_WorkGroupID.z;
    int line, block;
    const int M = pc.half_len;
    if (!line_item(plane, pc.lines_fastest != 0u, pc.lines, (M + BLOCK - 1) / BLOCK, line, block)) return;
    int o0 = block * BLOCK;
    const int Hf = F / 2;
    const int s = (Hf % 2 == 0) ? 1 : 0;
    const int first = o0 + F / 4 - Hf + 1;  // the windows' first coefficient
    float low[BLOCK + MAX_TAPS / 2 - 1], high[BLOCK + MAX_TAPS / 2 - 1];
    [[unroll]] for (int i = 0; i < BLOCK + Hf - 1; ++i) {
        int k = wrap_window(first + i, M);
        low[i] = BUF(src).v[src_at(plane, line, k)];
        high[i] = BUF(src).v[src_at(plane, line, M + k)];
    }
    [[unroll]] for (int b = 0; b < BLOCK; ++b) {
        if (o0 + b >= M) break;
        [[unroll]] for (int p = 0; p < 2; ++p) {
            Dot2 acc = dot2_of(0.0);
            [[unroll]] for (int j = 0; j < Hf; ++j) {  // coefficient o + start - j is window slot b + Hf - 1 - j
                TAP_ADD(acc, rec_lo(2 * j + p), low[b + Hf - 1 - j]);
                TAP_ADD(acc, rec_hi(2 * j + p), high[b + Hf - 1 - j]);
            }
            int m = 2 * (o0 + b) + p + s;
            if (m >= 2 * M) m -= 2 * M;
            if (m < pc.n) BUF(dst).v[dst_at(plane, line, m)] = TO_PLANE(dot2_result(acc));
        }
    }
}

#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "line.glsl"
// One level of pywt's periodization inverse DWT along a line (exactly
// upsampling_convolution_valid_sf_periodization for (low, rec_lo) plus
// (high, rec_hi)): with M = half_len coefficients per half, F taps, Hf = F/2,
// start = F/4 and a one-sample shift s = 1 when Hf is even (db2),
//   q = (m - s) mod 2M, o = q / 2, p = q mod 2
//   x[m] = sum_{j < Hf} rec_lo[2j + p] low[(o + start - j) mod M]
//                     + rec_hi[2j + p] high[(o + start - j) mod M]
// Only the first n of the 2M samples are written: pywt's crop for odd sizes.
layout(local_size_x = 16, local_size_y = 16) in;

void main() {
    uint plane = gl_WorkGroupID.z;
    int m = int(pc.x_is_line != 0u ? gl_GlobalInvocationID.y : gl_GlobalInvocationID.x);
    int line = int(pc.x_is_line != 0u ? gl_GlobalInvocationID.x : gl_GlobalInvocationID.y);
    if (m >= pc.n || line >= pc.lines) return;
    const int F = pc.wavelet;
    const int Hf = F / 2;
    const int M = pc.half_len;
    const int s = (Hf % 2 == 0) ? 1 : 0;
    int q = wrap_once(m - s, 2 * M);
    int o = q >> 1, p = q & 1;
    float acc = 0.0;
    for (int j = 0; j < Hf; ++j) {
        int k = wrap_once(o + F / 4 - j, M);
        acc += pc.filters.v[20 + 2 * j + p] * pc.src.v[src_at(plane, line, k)] +
               pc.filters.v[30 + 2 * j + p] * pc.src.v[src_at(plane, line, M + k)];
    }
    pc.dst.v[dst_at(plane, line, m)] = acc;
}

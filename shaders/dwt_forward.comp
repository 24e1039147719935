#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "line.glsl"
// One level of pywt's periodization DWT along a line (exactly
// downsampling_convolution_periodization): an odd line is first extended by
// repeating its last sample to even length N, then
//   low[o]  = sum_j dec_lo[j] * x[(F/2 + 2o - j) mod N]
//   high[o] = sum_j dec_hi[j] * x[(F/2 + 2o - j) mod N]
// for o < N/2; low goes to positions [0, N/2), high to [N/2, N).
layout(local_size_x = 16, local_size_y = 16) in;

void main() {
    uint plane = gl_WorkGroupID.z;
    int o = int(pc.x_is_line != 0u ? gl_GlobalInvocationID.y : gl_GlobalInvocationID.x);
    int line = int(pc.x_is_line != 0u ? gl_GlobalInvocationID.x : gl_GlobalInvocationID.y);
    if (o >= pc.half_len || line >= pc.lines) return;
    const int F = pc.wavelet;
    const int N = 2 * pc.half_len;
    float lo = 0.0, hi = 0.0;
    for (int j = 0; j < F; ++j) {
        int m = wrap_once(F / 2 + 2 * o - j, N);
        float x = pc.src.v[src_at(plane, line, min(m, pc.n - 1))];  // m == n: the repeated last sample
        lo += pc.filters.v[j] * x;
        hi += pc.filters.v[10 + j] * x;
    }
    pc.dst.v[dst_at(plane, line, o)] = lo;
    pc.dst.v[dst_at(plane, line, pc.half_len + o)] = hi;
}

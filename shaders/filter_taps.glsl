// The periodization filter bank as specialization constants (constant_id 0:
// the filter length F; 1..10 dec_lo, 11..20 dec_hi, 21..30 rec_lo, 31..40
// rec_hi, each zero-padded to 10 taps), set per wavelet when the plan builds
// the pipeline. With F known when the pipeline is compiled, the tap loops
// unroll and every tap is an immediate: no filter loads, no index arithmetic.
// VKFUSE_FILTER_CONSTANTS (kernel_codes.h) counts them.
const int MAX_TAPS = 10;
layout(constant_id = 0) const int F = 2;
layout(constant_id = 1) const float DL0 = 0.0;
layout(constant_id = 2) const float DL1 = 0.0;
layout(constant_id = 3) const float DL2 = 0.0;
layout(constant_id = 4) const float DL3 = 0.0;
layout(constant_id = 5) const float DL4 = 0.0;
layout(constant_id = 6) const float DL5 = 0.0;
layout(constant_id = 7) const float DL6 = 0.0;
layout(constant_id = 8) const float DL7 = 0.0;
layout(constant_id = 9) const float DL8 = 0.0;
layout(constant_id = 10) const float DL9 = 0.0;
layout(constant_id = 11) const float DH0 = 0.0;
layout(constant_id = 12) const float DH1 = 0.0;
layout(constant_id = 13) const float DH2 = 0.0;
layout(constant_id = 14) const float DH3 = 0.0;
layout(constant_id = 15) const float DH4 = 0.0;
layout(constant_id = 16) const float DH5 = 0.0;
layout(constant_id = 17) const float DH6 = 0.0;
layout(constant_id = 18) const float DH7 = 0.0;
layout(constant_id = 19) const float DH8 = 0.0;
layout(constant_id = 20) const float DH9 = 0.0;
layout(constant_id = 21) const float RL0 = 0.0;
layout(constant_id = 22) const float RL1 = 0.0;
layout(constant_id = 23) const float RL2 = 0.0;
layout(constant_id = 24) const float RL3 = 0.0;
layout(constant_id = 25) const float RL4 = 0.0;
layout(constant_id = 26) const float RL5 = 0.0;
layout(constant_id = 27) const float RL6 = 0.0;
layout(constant_id = 28) const float RL7 = 0.0;
layout(constant_id = 29) const float RL8 = 0.0;
layout(constant_id = 30) const float RL9 = 0.0;
layout(constant_id = 31) const float RH0 = 0.0;
layout(constant_id = 32) const float RH1 = 0.0;
layout(constant_id = 33) const float RH2 = 0.0;
layout(constant_id = 34) const float RH3 = 0.0;
layout(constant_id = 35) const float RH4 = 0.0;
layout(constant_id = 36) const float RH5 = 0.0;
layout(constant_id = 37) const float RH6 = 0.0;
layout(constant_id = 38) const float RH7 = 0.0;
layout(constant_id = 39) const float RH8 = 0.0;
layout(constant_id = 40) const float RH9 = 0.0;
// Tap j of each filter (a constant array of specialization constants is not
// allowed for floats): once the loops unroll, j is constant and the select
// chains fold to one immediate.
#define VKFUSE_TAP(P, j) ((j) == 0 ? P##0 : (j) == 1 ? P##1 : (j) == 2 ? P##2 : (j) == 3 ? P##3 : (j) == 4 ? P##4 : \
    (j) == 5 ? P##5 : (j) == 6 ? P##6 : (j) == 7 ? P##7 : (j) == 8 ? P##8 : P##9)
// A filter tap adds to a compensated sum only where it is not zero (pywt pads
// bior filters with zeros: 4 of bior4.4's 20 analysis taps). With the taps
// specialization constants the test folds away, and a zero tap would add
// exactly nothing (a product of 0 and its error terms 0), so skipping it
// changes no bit.
#define TAP_ADD(acc, tap, x) if ((tap) != 0.0) dot2_add(acc, tap, x)
float dec_lo(int j) { return VKFUSE_TAP(DL, j); }
float dec_hi(int j) { return VKFUSE_TAP(DH, j); }
float rec_lo(int j) { return VKFUSE_TAP(RL, j); }
float rec_hi(int j) { return VKFUSE_TAP(RH, j); }

// Outputs per invocation along the line: each keeps a window of the samples
// its outputs share in registers, so a sample is loaded about once per
// invocation that needs it instead of once per filter tap.
const int BLOCK = VKFUSE_CONV_BLOCK;

// a mod m for a in [-m, 2m), then clamped into [0, m): the clamp only touches
// windows of invocations whose outputs fall past the end (never stored), and
// keeps their loads in bounds on lines shorter than the window.
int wrap_window(int a, int m) {
    return min(a < 0 ? a + m : (a >= m ? a - m : a), m - 1);
}

// The forward kernels' register window: the samples an invocation's BLOCK
// output pairs o0 .. o0 + BLOCK - 1 read, x[F/2 + 2 o0 - (F - 1) + i] for
// i < 2 BLOCK + F - 2, periodic over the line's even length 2 half_len, with
// an odd line's missing last sample repeating sample n - 1.
const int WINDOW = 2 * BLOCK + MAX_TAPS - 2;

int window_sample(int o0, int i, int half_len, int n) {
    return min(wrap_window(F / 2 + 2 * o0 - (F - 1) + i, 2 * half_len), n - 1);
}

// pywt's analysis of output pair o0 + b from the window: (low, high), each a
// compensated dot product (Dot2) rounded once; x[F/2 + 2o - j] is slot
// 2b + F - 1 - j.
vec2 analyse(float win[WINDOW], int b) {
    Dot2 lo = dot2_of(0.0), hi = dot2_of(0.0);
    [[unroll]] for (int j = 0; j < F; ++j) {
        TAP_ADD(lo, dec_lo(j), win[2 * b + F - 1 - j]);
        TAP_ADD(hi, dec_hi(j), win[2 * b + F - 1 - j]);
    }
    return vec2(dot2_result(lo), dot2_result(hi));
}

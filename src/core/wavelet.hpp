// core/wavelet.hpp - the separable 2-D DWT of the `wavelet` fusion method, in
// double precision: PyWavelets' filter banks, its periodization mode (exactly),
// and a symmetric-extension lifting mode. Every formula below is what the GPU
// shaders port, so it is spelled out with exact index arithmetic.
//
// Notation: mod(a, m) is the non-negative remainder ((a % m) + m) % m;
// integer division truncates; R(p, n) is reflect101 from core/border.hpp.
//
// ---------------------------------------------------------------------------
// PERIODIZATION (pywt MODE_PERIODIZATION; pywt/_extensions/c/convolution.template.c)
//
// Analysis, one line x[0..N-1] -> approx a[0..M-1], detail d[0..M-1], M = ceil(N/2):
//   Np    = N + (N mod 2)                  (odd N: the last sample is repeated once)
//   xe(t) = x[min(t, N - 1)]               for 0 <= t < Np
//   a[o]  = sum_{j=0}^{F-1} dec_lo[j] * xe(mod(2 o + F/2 - j, Np))
//   d[o]  = sum_{j=0}^{F-1} dec_hi[j] * xe(mod(2 o + F/2 - j, Np))
//   (F = FilterBank::length; this is downsampling_convolution_periodization
//   with step 2, its padding and wrap-around loops folded into mod and min.)
//
// Synthesis, a[0..N-1], d[0..N-1] -> y[0..2N-1] (upsampling_convolution_valid_sf_periodization
// applied to (a, rec_lo) and (d, rec_hi), summed):
//   Hf    = F / 2                          (taps per output phase)
//   start = F / 4                          (integer division)
//   s     = (Hf even) ? 1 : 0              (pywt shifts the output one sample right
//                                           when F/2 is even: db2 only)
//   for n in 0..2N-1:
//     q = mod(n - s, 2N), m = q / 2, p = q mod 2
//     y[n] = sum_{j=0}^{Hf-1} rec_lo[2j + p] * a[mod(m + start - j, N)]
//                           + rec_hi[2j + p] * d[mod(m + start - j, N)]
//
// 2-D, one level (pywt dwtn/idwtn with axes (0, 1)): analysis runs along axis 0
// (down every column) first, then along axis 1 (along every row) on both results;
// synthesis runs along axis 1 first, then axis 0. Bands of an h x w input are all
// ceil(h/2) x ceil(w/2); synthesis returns 2*ceil(h/2) x 2*ceil(w/2).
//
// Multi-level (pywt.wavedec2 / waverec2, mode="periodization", level=L):
//   analysis: A_0 = image (h_0 x w_0); A_{l+1}, bands_{l+1} = dwt2(A_l); sizes
//   h_{l+1} = ceil(h_l / 2). Synthesis: A = A_L; for l = L-1 .. 0:
//   A = crop(idwt2(A, bands_{l+1}), h_l x w_l) (top-left corner). This equals
//   waverec2's "drop the last row/column of the approximation when it is one
//   longer than the detail" followed by cropping pywt's even-sized result to the
//   input shape.
//
// ---------------------------------------------------------------------------
// SYMMETRIC (lifting with whole-sample symmetric extension; not pywt's "symmetric")
//
// One line x[0..n-1], n >= 2, is lifted in place: even positions carry the
// approximation, odd positions the detail. A step "odd += c (o1, o2)" means
//   for every odd  q < n: x[q] += c1 * x[R(q + o1, n)] + c2 * x[R(q + o2, n)]
// and "even += ..." the same for every even p < n. A step only writes one parity
// and (because R keeps parity) only reads the other, so it is one parallel pass.
// Then approx[i] = x[2i] * Ke (i < ceil(n/2)), detail[i] = x[2i+1] * Ko (i < floor(n/2)).
// Inverse: x[2i] = approx[i] / Ke, x[2i+1] = detail[i] / Ko, then the steps in
// reverse order with += replaced by -=. Perfect reconstruction for every n.
// A line of length 1 has no detail: approx[0] = x[0] (copied, not scaled).
//
//   haar:    odd  += -1 (q-1)
//            even += 1/2 (p+1)
//            Ke = sqrt(2), Ko = -1/sqrt(2)
//   db2:     odd  += -sqrt(3) (q-1)                                 (Daubechies-Sweldens)
//            even += sqrt(3)/4 (p+1), (sqrt(3)-2)/4 (p+3)
//            odd  += 1 (q-3)
//            Ke = (sqrt(3)+1)/sqrt(2), Ko = -(sqrt(3)-1)/sqrt(2)
//   bior2.2: odd  += -1/2 (q-1), -1/2 (q+1)                          (CDF 5/3)
//            even += 1/4 (p-1), 1/4 (p+1)
//            Ke = sqrt(2), Ko = -1/sqrt(2)
//   bior4.4: odd  += alpha (q-1), alpha (q+1)                        (CDF 9/7)
//            even += beta  (p-1), beta  (p+1)
//            odd  += gamma (q-1), gamma (q+1)
//            even += delta (p-1), delta (p+1)
//            alpha = -1.586134342059924, beta = -0.05298011857296141,
//            gamma = 0.8829110755309333, delta = 0.4435068520439711,
//            Ke = sqrt(2) / (1 + 2 beta (1 + 2 alpha)) (= 1.1496043988602411), Ko = -1/Ke
// Ke makes the lowpass DC gain exactly sqrt(2), like pywt's filters; the signs of
// Ko make interior coefficients equal pywt's periodization coefficients (haar,
// bior2.2 exactly; bior4.4 to ~5e-13, the precision of pywt's tabulated
// filters; db2 equals pywt's dwt of the line advanced by one sample, with the
// detail index shifted by one, because this factorisation centres the lowpass
// on even samples).
//
// 2-D: the same axis order as periodization. Bands of an h x w input:
//   approx ceil(h/2) x ceil(w/2), horizontal ('da') floor(h/2) x ceil(w/2),
//   vertical ('ad') ceil(h/2) x floor(w/2), diagonal ('dd') floor(h/2) x floor(w/2);
//   synthesis returns exactly h x w (no cropping).
#pragma once
#include <array>
#include <span>
#include <vector>

#include "core/plane.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse::core {

// PyWavelets' Wavelet(name).filter_bank, bit for bit; entries past `length` are 0.
struct FilterBank {
    int length = 0;
    std::array<double, 10> dec_lo{}, dec_hi{}, rec_lo{}, rec_hi{};
};
const FilterBank& filter_bank(Wavelet w);

// One lifting step (see above): x[q] += sum_t coef[t] * x[R(q + offset[t], n)]
// for every q of the given parity.
struct LiftingStep {
    int parity = 0;  // 1: odd positions (detail), 0: even positions (approximation)
    int taps = 0;    // 1 or 2
    std::array<double, 2> coef{};
    std::array<int, 2> offset{};
};

struct LiftingScheme {
    int steps = 0;
    std::array<LiftingStep, 4> step{};
    double scale_even = 1;  // Ke
    double scale_odd = 1;   // Ko
};
const LiftingScheme& lifting_scheme(Wavelet w);

// 1-D transforms. Periodization: approx and detail both hold ceil(n/2);
// synthesis takes two equal lengths N and writes 2N. Lifting: approx ceil(n/2),
// detail floor(n/2); synthesis writes approx.size() + detail.size().
void dwt_periodization(std::span<const double> x, const FilterBank& fb, std::span<double> approx,
                       std::span<double> detail);
void idwt_periodization(std::span<const double> approx, std::span<const double> detail, const FilterBank& fb,
                        std::span<double> out);
void dwt_lifting(std::span<const double> x, const LiftingScheme& ls, std::span<double> approx,
                 std::span<double> detail);
void idwt_lifting(std::span<const double> approx, std::span<const double> detail, const LiftingScheme& ls,
                  std::span<double> out);

// One decomposition level: the size of the approximation it split and its
// three detail bands, named as pywt.dwt2 returns them (cH, cV, cD).
struct WaveletLevel {
    int height = 0;
    int width = 0;
    Plane horizontal;  // pywt cH, key 'da': detail along axis 0, approx along axis 1
    Plane vertical;    // pywt cV, key 'ad': approx along axis 0, detail along axis 1
    Plane diagonal;    // pywt cD, key 'dd'
};

// A multi-level decomposition. levels[0] is level 1 (finest, decomposing the
// image itself); levels.back() is level L, whose approximation is `approx`.
// pywt.wavedec2 lists the same data coarsest first: [approx, levels[L-1], ..., levels[0]].
struct WaveletCoeffs {
    Plane approx;
    std::vector<WaveletLevel> levels;
};

// L >= 1 levels of plane in the given mode (no level-count check: validate() does that).
WaveletCoeffs wavedec2(const Plane& plane, Wavelet w, WaveletMode mode, int levels);
// The inverse; returns levels[0].height x levels[0].width.
Plane waverec2(const WaveletCoeffs& coeffs, Wavelet w, WaveletMode mode);

}  // namespace vkfuse::core

#include "vk/engine/magnitude.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace vkfuse::vk {
namespace {

// No scaling while a sensor's largest magnitude lies in [2^-40, 2^40): the
// ordinary path (inputs in [0, 1], 8-bit frames) stays bit for bit as it was.
constexpr double kBandLow = 0x1p-40, kBandHigh = 0x1p40;
// Whatever scale is chosen, the largest scaled value stays below 2^64 (metric
// sums of 2^34 such terms stay below 2^98) and the frames' largest >= 2^-64
// (their significant bits stay far above float's 2^-126), or >= 2^-40, the
// band's low edge, on a device that may flush subnormals: there the squares
// the metrics sum (2^-80 and a deviation's 2^-40 below) must stay normal too.
constexpr int kKeepLowExponent = -64, kKeepLowFlushingExponent = -40;
constexpr double kKeepHigh = 0x1p64;
// Brovey's 1e-6 threshold times 2^-e must stay a normal float with room for
// the sums compared with it (1e-6 * 2^-100 = 7.9e-37 >= 2^-126 = 1.2e-38);
// with e <= 100 the scaled frames stay below 2^28.
constexpr int kBroveyMaxExponent = 100;

float from_bits(std::uint32_t bits) { return std::bit_cast<float>(bits); }

// e with v in [2^(e-1), 2^e), v > 0.
int exponent_of(double v) {
    int e = 0;
    std::frexp(v, &e);
    return e;
}

}  // namespace

float load(const void* values, std::size_t i) {
    float v;
    std::memcpy(&v, static_cast<const unsigned char*>(values) + i * sizeof(float), sizeof v);
    return v;
}

std::uint32_t copy_magnitude(float* dst, const void* src, std::size_t n) {
    std::int16_t m = 0;  // the high half of |x|'s bits: sign (0), exponent, 7 mantissa bits
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t w;
        std::memcpy(&w, static_cast<const unsigned char*>(src) + i * sizeof w, sizeof w);
        std::memcpy(dst + i, &w, sizeof w);
        const auto high = std::int16_t((w >> 16) & 0x7fffu);
        m = high > m ? high : m;
    }
    return std::uint32_t(m) << 16;
}

std::uint32_t max_abs(const void* src, std::size_t n) {
    std::uint32_t m = 0;
    for (std::size_t i = 0; i < n; ++i) m = std::max(m, std::bit_cast<std::uint32_t>(load(src, i)) & kAbsMask);
    return m;
}

void copy_scaled(float* dst, const void* src, std::size_t n, int exponent) {
    // A power of two is exact in double for any float exponent: one rounding,
    // and none at all unless the result leaves float's normal range.
    const double factor = std::ldexp(1.0, -exponent);
    for (std::size_t i = 0; i < n; ++i) dst[i] = float(double(load(src, i)) * factor);
}

std::size_t scale_back(float* dst, const float* src, std::size_t n, int exponent) {
    const double factor = std::ldexp(1.0, exponent), largest = std::numeric_limits<float>::max();
    std::size_t beyond = n;
    for (std::size_t i = 0; i < n; ++i) {
        double v = double(src[i]) * factor;  // exact: 24 significant bits at another exponent
        if (std::abs(v) > largest) {        // so at least 2^128: no float holds it
            if (beyond == n) beyond = i;
            v = 0;
        }
        dst[i] = float(v);
    }
    return beyond;
}

std::size_t first_non_finite(const void* values, std::size_t n) {
    std::uint32_t any = 0;  // one branch-free pass first: the common case finds nothing
    for (std::size_t i = 0; i < n; ++i)
        any |= (std::bit_cast<std::uint32_t>(load(values, i)) & kNonFinite) == kNonFinite;  // exponent all ones
    if (!any) return n;
    std::size_t i = 0;
    while (i < n && std::isfinite(load(values, i))) ++i;
    return i;
}

std::optional<int> choose_exponent(std::uint32_t frames_max, std::uint32_t background_max, bool brovey,
                                   bool keeps_subnormals) {
    const double f = from_bits(frames_max), m = std::max(f, double(from_bits(background_max)));
    if (m == 0) return 0;
    const int keep_low = keeps_subnormals ? kKeepLowExponent : kKeepLowFlushingExponent;
    const auto fits = [&](int e) {
        const double ms = std::ldexp(m, -e), fs = std::ldexp(f, -e);
        return ms < kKeepHigh && (f == 0 ? ms : fs) >= std::ldexp(1.0, keep_low);
    };
    if (m >= kBandLow && m < kBandHigh && fits(0)) return 0;
    int e = exponent_of(m);  // largest scaled magnitude in [0.5, 1)
    // Frames far below the background: theirs in [2^keep_low, 2^(keep_low + 1)).
    if (!fits(e) && f > 0) e = exponent_of(f) - keep_low - 1;
    if (brovey) e = std::min(e, kBroveyMaxExponent);
    if (!fits(e)) return std::nullopt;
    return e;
}

float brovey_threshold(int exponent) {
    // The smallest float >= 1e-6, as the kernel's unscaled threshold: scaled
    // by a power of two it stays the smallest float >= 1e-6 * 2^-e. Below
    // e = -108 it passes FLT_MAX, which no scaled sum (<= K) reaches either.
    const double t = std::ldexp(double(std::nextafter(1e-6f, 1.0f)), -exponent);
    return t > double(std::numeric_limits<float>::max()) ? std::numeric_limits<float>::max() : float(t);
}

}  // namespace vkfuse::vk

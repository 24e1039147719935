// How a plan keeps float32 frames of any magnitude inside the range its
// kernels compute in (docs/architecture.md, "Magnitudes").
//
// Every method and metric is positively homogeneous of degree 1 except
// Brovey's absolute dark threshold, and multiplying by a power of two changes
// no rounding. So where a sensor's frames (and background) lie outside
// [2^-40, 2^40), Plan::run multiplies them by 2^-e while copying them to the
// device (their largest magnitude then in [0.5, 1)), Brovey compares against
// its threshold times 2^-e, and fused images and metrics are multiplied by
// 2^e on read-back. Inside the band e = 0 and nothing changes: the kernels'
// largest intermediate (pyrDown's 256-weight sums, 2^28 metric terms) stays
// far below FLT_MAX, and the smallest significant value far above 2^-126.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>

namespace vkfuse::vk {

// |x| of a float32 as its bit pattern: ordered like |x| for finite values;
// kNonFinite or above means Inf or NaN.
constexpr std::uint32_t kAbsMask = 0x7fffffffu;
constexpr std::uint32_t kNonFinite = 0x7f800000u;

// Sources are n floats at any address (a caller's frame buffer need not be
// 4-byte aligned).
// Copies n floats and returns their largest |x| as float bits truncated to the
// exponent and 7 mantissa bits: enough for every decision here (they compare
// with powers of two), and a maximum over 16-bit halves runs near memcpy's
// speed on any x86-64 where the exact one takes three times as long. 0 for
// zeros and subnormals below 2^-133 alone; kNonFinite or above if any is Inf
// or NaN.
std::uint32_t copy_magnitude(float* dst, const void* src, std::size_t n);
// Largest |x| as bits, exact.
std::uint32_t max_abs(const void* src, std::size_t n);
// dst[i] = src[i] * 2^-exponent, rounded once.
void copy_scaled(float* dst, const void* src, std::size_t n, int exponent);
// dst[i] = src[i] * 2^exponent (a result read back, to the frames' scale).
// Returns the index of the first value beyond float's range (left 0 in dst),
// or n.
std::size_t scale_back(float* dst, const float* src, std::size_t n, int exponent);
// Index of the first NaN or Inf, or n.
std::size_t first_non_finite(const void* values, std::size_t n);
// values[i].
float load(const void* values, std::size_t i);

// The exponent e of one sensor's scale (the device gets x * 2^-e), from the
// largest magnitudes of its frames and of its background (bits, 0 if none;
// exact or as copy_magnitude truncates them, unless that gave 0).
// nullopt when no single scale holds both (frames more than ~2^127 below
// the background, or ~2^103 on a device that may flush subnormals:
// keeps_subnormals false, DeviceInfo::float32_subnormals). brovey caps e where
// its threshold would leave float's normal range.
std::optional<int> choose_exponent(std::uint32_t frames_max, std::uint32_t background_max, bool brovey,
                                   bool keeps_subnormals);

// Brovey's s >= 1e-6 in a sensor's scaled domain.
float brovey_threshold(int exponent);

}  // namespace vkfuse::vk

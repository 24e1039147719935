// io/limits.hpp - the largest image the readers accept.
#pragma once
#include <cstdint>
#include <string>

namespace vkfuse::io {

// 2^28 samples (1 GiB of float32, e.g. 16384 x 16384 gray): far above any
// tactile frame, and low enough that a corrupt header claiming a gigantic
// image is refused instead of exhausting memory. It also keeps every
// dimension and index within int.
inline constexpr std::uint64_t kMaxSamples = std::uint64_t(1) << 28;

// Throws Error(Format) naming path when height x width x channels exceeds
// kMaxSamples or a dimension is zero.
void check_image_size(const std::string& path, std::uint64_t height, std::uint64_t width, std::uint64_t channels);

}  // namespace vkfuse::io

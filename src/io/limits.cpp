#include "io/limits.hpp"

#include "io/io_error.hpp"

namespace vkfuse::io {

void check_image_size(const std::string& path, std::uint64_t height, std::uint64_t width, std::uint64_t channels) {
    if (height == 0 || width == 0 || channels == 0) fail(ErrorKind::Format, path, "empty image (a dimension is 0)");
    // Divide rather than multiply so a corrupt 64-bit dimension cannot overflow.
    if (width > kMaxSamples / channels || height > kMaxSamples / (width * channels))
        fail(ErrorKind::Format, path,
             "image too large: " + std::to_string(height) + "x" + std::to_string(width) + "x" +
                 std::to_string(channels) + " exceeds the limit of " + std::to_string(kMaxSamples) + " samples");
}

}  // namespace vkfuse::io

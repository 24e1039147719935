// io/image_header.hpp - what an image file's header promises, read without
// decoding a pixel: enough to check shapes and plan memory before the work.
#pragma once
#include <cstdint>
#include <string>

namespace vkfuse::io {

struct ImageHeader {
    int height = 0, width = 0;
    int channels = 0;                // as read_image returns it: 1 or 3
    std::uint64_t decode_bytes = 0;  // working memory of the decode beyond the image itself

    std::uint64_t samples() const { return std::uint64_t(height) * std::uint64_t(width) * std::uint64_t(channels); }
    std::uint64_t image_bytes() const { return samples() * sizeof(float); }  // the decoded Image
};

// The header of the .png or .npy file at path, checked as read_image checks
// it (format, dimensions and their limit, a size the file can hold; for .npy
// the exact data size), reading only the header. Throws what read_image
// throws for those problems; the pixels are not looked at.
ImageHeader read_image_header(const std::string& path);

}  // namespace vkfuse::io

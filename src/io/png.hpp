// io/png.hpp - PNG decoding and encoding with libpng (SPEC.md, "Images").
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "vkfuse/image.hpp"

namespace vkfuse::io {

// Decodes a whole PNG file held in memory: any color type and bit depth,
// palette and low bit depths expanded, alpha dropped, v/255 or v/65535.
// Throws Error(Format) "path: <problem>" for anything that is not a valid PNG.
Image decode_png(const std::vector<unsigned char>& file, const std::string& path);

// Writes image (C = 1 or 3, finite) as an 8-bit gray or RGB PNG, each value
// clamped to [0, 1] and rounded: round(v * 255). Throws Error naming path.
void write_png(std::FILE* out, const Image& image, const std::string& path);

}  // namespace vkfuse::io

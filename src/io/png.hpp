// io/png.hpp - PNG decoding and encoding with libpng (docs/spec.md, "Images").
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "io/image_header.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::io {

class InputFile;

// Decodes a whole PNG file held in memory: any color type and bit depth,
// palette and low bit depths expanded, alpha dropped, v/255 or v/65535.
// Throws Error(Format) "path: <problem>" for anything that is not a valid PNG.
Image decode_png(const std::vector<unsigned char>& file, const std::string& path);

// The same from a file, streamed through libpng: the signature and the chunks
// up to the image data are read and checked (dimensions, a size the file can
// hold) before anything is allocated for pixels; non-interlaced rows are
// converted one at a time. Reads at most what an image of the header's size
// can occupy (rows stored uncompressed, twice, plus 128 MiB of metadata) and
// nothing after IEND, so a huge file behind a small header is not read.
ImageHeader read_png_header(InputFile& file);
Image read_png(InputFile& file);

// How hard the writer compresses: Small (zlib's default level, adaptive
// filters) for files, Fast (level 1, one filter: a few times quicker, a
// little larger) for the live server's images, written every cycle.
enum class PngSpeed { Small, Fast };

// Writes image (C = 1 or 3, finite) as an 8-bit gray or RGB PNG: to_8bit's
// samples, the same whatever the speed. Throws Error naming path.
void write_png(std::FILE* out, const Image& image, const std::string& path, PngSpeed speed = PngSpeed::Small);

// An image's samples as 8-bit PNGs (and rgb8 ROS images) hold them: each
// value clamped to [0, 1] and rounded, round(v * 255).
std::vector<unsigned char> to_8bit(const Image& image);

}  // namespace vkfuse::io

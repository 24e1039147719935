// io/npy.hpp - NumPy .npy arrays as images (docs/spec.md, "Images").
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "io/image_header.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::io {

class InputFile;

// Decodes a whole .npy file held in memory: float32/float64 as is, uint8 v/255,
// uint16 v/65535, either byte order, C or Fortran order, shape (H, W) or
// (H, W, C) with C in {1, 3, 4} (alpha dropped). The data size is checked
// against the header before anything is allocated. Throws Error(Format).
Image decode_npy(const std::vector<unsigned char>& file, const std::string& path);

// The same from a file: the header is read and checked first, and the file
// must hold exactly the data it declares (its size, from fstat, is compared
// before any data is read), so a huge or sparse file behind a small header
// is refused without reading it. C-order data is read and converted in
// chunks of about 4 MiB; Fortran order is read whole.
ImageHeader read_npy_header(InputFile& file);
Image read_npy(InputFile& file);

// Writes image as little-endian float32, shape (H, W) when C = 1, else (H, W, C).
void write_npy(std::FILE* out, const Image& image, const std::string& path);

}  // namespace vkfuse::io

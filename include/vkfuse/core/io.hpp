// vkfuse/core/io.hpp - PNG and NPY images, with docs/spec.md's value mapping.
#pragma once
#include <string>

#include "vkfuse/core/image.hpp"

namespace vkfuse::io {

// Reads by extension (.png, .npy; case-insensitive). PNG: 8/16-bit gray, gray+alpha,
// RGB, RGBA (alpha dropped; palette expanded), v/255 or v/65535. NPY: float32,
// float64, uint8 (v/255), uint16 (v/65535), shape (H, W) or (H, W, C) with C in
// {1, 3} (C = 4 drops alpha), C or Fortran order. Throws Error naming the path and
// the problem (Io: missing/unreadable; Format: corrupt/unsupported; Numeric: NaN/Inf).
Image read_image(const std::string& path);

// Writes by extension: .npy stores float32 (H, W, C) as computed (C = 1 as (H, W));
// .png clamps to [0, 1] and rounds to 8 bits. Writes a temporary file beside path
// and renames it, so a failure never leaves a partial file. Throws Error(Io/InvalidArgument).
void write_image(const std::string& path, const Image& image);

// Throws Error(InvalidArgument) "path: unknown image format ..." unless path ends
// in .png or .npy (case-insensitive), so a caller can reject an output name
// before computing what it would hold.
void check_image_extension(const std::string& path);

// Throws Error(Numeric) "<what>: NaN at row y, column x, channel c" if any value is not finite.
void check_finite(const Image& image, const std::string& what);

}  // namespace vkfuse::io

// frame_codec.hpp - what a UVC camera sends, YUYV 4:2:2 and Motion-JPEG,
// to 8-bit RGB (HWC) and back (the way back for emulated cameras and tests).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vkfuse {

// YUYV (Y0 U Y1 V per pixel pair) in BT.601 limited range, the encoding UVC
// cameras use for uncompressed video, to RGB: R = 1.164 (Y - 16) + 1.596 (V - 128),
// G = 1.164 (Y - 16) - 0.392 (U - 128) - 0.813 (V - 128), B = 1.164 (Y - 16) + 2.017 (U - 128),
// in 8.8 fixed point, clamped to 0..255. `yuyv` holds width * height * 2 bytes
// (width even); returns false when it holds fewer.
bool yuyv_to_rgb(std::span<const std::uint8_t> yuyv, int width, int height, std::vector<std::uint8_t>& rgb);

// The inverse, for emulators and tests: RGB (width even) to YUYV, each pair's
// chroma the mean of its two pixels'.
std::vector<std::uint8_t> rgb_to_yuyv(std::span<const std::uint8_t> rgb, int width, int height);

// One Motion-JPEG frame to RGB. A frame that does not decode cleanly to
// exactly width x height x 3 (a libjpeg error or even a warning, such as data
// cut short, which libjpeg would otherwise paper over with grey) returns
// false with the reason in `why`. Frames without Huffman tables, as UVC
// cameras send them, take the standard tables.
bool mjpeg_to_rgb(std::span<const std::uint8_t> jpeg, int width, int height, std::vector<std::uint8_t>& rgb,
                  std::string& why);

// RGB to one baseline JPEG frame (4:2:2 chroma, as UVC cameras send), quality 1..100.
std::vector<std::uint8_t> rgb_to_jpeg(std::span<const std::uint8_t> rgb, int width, int height, int quality);

}  // namespace vkfuse

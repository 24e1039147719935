// run/caption.hpp - text on the pictures `vkfuse run --out` writes: a band of
// labelled lines above a picture, in an anti-aliased 7 x 11 font (printable
// ASCII; anything else shows as '?'), so a shared side-by-side picture says
// what it compares.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/core/image.hpp"

namespace vkfuse::cli {

inline constexpr int kGlyphWidth = 7, kGlyphHeight = 11;

// Draws text with its top-left corner at (x, y), each glyph scale x scale
// pixels per cell pixel, blended over what is there; clipped to the image.
void draw_text(Image& image, int x, int y, std::string_view text, const float (&colour)[3], int scale);

// One line of a caption: its text and where it starts (a column of the picture).
struct CaptionText {
    std::string text;
    int x = 0;
};
using CaptionLine = std::vector<CaptionText>;

// picture (RGB) below a dark band holding lines, light text; the band's
// height follows the line count and scale.
Image with_caption(const Image& picture, const std::vector<CaptionLine>& lines, int scale);

}  // namespace vkfuse::cli

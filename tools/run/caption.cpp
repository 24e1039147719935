// Text drawn into images (caption.hpp) from the generated glyph table.
#include "run/caption.hpp"

#include <algorithm>
#include <cstdint>

namespace vkfuse::cli {
namespace {

constexpr std::uint8_t kGlyphs[][kGlyphWidth * kGlyphHeight] = {
#include "run/caption_font.inc"
};
constexpr char kFirst = 32, kLast = 126;
constexpr float kBand[3] = {0.08f, 0.08f, 0.1f};
constexpr float kInk[3] = {0.92f, 0.92f, 0.94f};

}  // namespace

void draw_text(Image& image, int x, int y, std::string_view text, const float (&colour)[3], int scale) {
    for (char ch : text) {
        const std::uint8_t* g = kGlyphs[(ch >= kFirst && ch <= kLast ? ch : '?') - kFirst];
        for (int gy = 0; gy < kGlyphHeight * scale; ++gy)
            for (int gx = 0; gx < kGlyphWidth * scale; ++gx) {
                const int px = x + gx, py = y + gy;
                if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
                const float a = float(g[(gy / scale) * kGlyphWidth + gx / scale]) / 255.0f;
                for (int c = 0; c < image.channels && c < 3; ++c)
                    image.at(py, px, c) = image.at(py, px, c) * (1 - a) + colour[c] * a;
            }
        x += kGlyphWidth * scale;
    }
}

Image with_caption(const Image& picture, const std::vector<CaptionLine>& lines, int scale) {
    const int line_height = (kGlyphHeight + 5) * scale;
    const int band = int(lines.size()) * line_height + 4 * scale;
    Image out(picture.height + band, picture.width, picture.channels);
    for (int y = 0; y < band; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < out.channels; ++c) out.at(y, x, c) = kBand[std::min(c, 2)];
    std::copy(picture.data.begin(), picture.data.end(), out.data.begin() + std::ptrdiff_t(band) * out.width * out.channels);
    for (std::size_t i = 0; i < lines.size(); ++i)
        for (const CaptionText& t : lines[i])
            draw_text(out, t.x + 3 * scale, 3 * scale + int(i) * line_height, t.text, kInk, scale);
    return out;
}

}  // namespace vkfuse::cli

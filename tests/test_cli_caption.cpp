// The captions of `vkfuse run`'s side-by-side pictures (tools/run/caption):
// glyphs land in their cells, blended over what is there; a caption band
// keeps the picture below it as it was.
#include <gtest/gtest.h>

#include <algorithm>

#include "run/caption.hpp"

namespace vkfuse::test {
namespace {

using cli::draw_text;
using cli::kGlyphHeight;
using cli::kGlyphWidth;
using cli::with_caption;

constexpr float kWhite[3] = {1, 1, 1};

float ink(const Image& im, int x0, int y0, int w, int h) {
    float sum = 0;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x) sum += im.at(y, x, 0);
    return sum;
}

TEST(Caption, GlyphsLandInTheirCellsAndSpacesDrawNothing) {
    Image im(30, 60, 3);
    draw_text(im, 5, 4, "A B", kWhite, 1);
    EXPECT_GT(ink(im, 5, 4, kGlyphWidth, kGlyphHeight), 5.0f);                    // A
    EXPECT_EQ(ink(im, 5 + kGlyphWidth, 4, kGlyphWidth, kGlyphHeight), 0.0f);      // the space
    EXPECT_GT(ink(im, 5 + 2 * kGlyphWidth, 4, kGlyphWidth, kGlyphHeight), 5.0f);  // B
    // Nothing outside the three cells.
    const float all = ink(im, 0, 0, im.width, im.height);
    EXPECT_FLOAT_EQ(all, ink(im, 5, 4, 3 * kGlyphWidth, kGlyphHeight));
}

TEST(Caption, OtherCharactersShowAsAQuestionMarkAndScaleRepeatsPixels) {
    Image a(12, 8, 3), b(12, 8, 3);
    draw_text(a, 0, 0, "\xc3", kWhite, 1);
    draw_text(b, 0, 0, "?", kWhite, 1);
    EXPECT_EQ(a.data, b.data);
    Image big(2 * kGlyphHeight, 2 * kGlyphWidth, 3);
    draw_text(big, 0, 0, "x", kWhite, 2);
    for (int y = 0; y < kGlyphHeight; ++y)
        for (int x = 0; x < kGlyphWidth; ++x) EXPECT_EQ(big.at(2 * y, 2 * x, 0), big.at(2 * y + 1, 2 * x + 1, 0));
    // Clipped at the edges, never written past them.
    Image small(3, 3, 3);
    draw_text(small, -4, -4, "WWW", kWhite, 1);
}

TEST(Caption, TheBandSitsAboveThePictureUnchanged) {
    Image picture(20, 90, 3);
    for (std::size_t i = 0; i < picture.data.size(); ++i) picture.data[i] = float(i % 7) / 7.0f;
    const Image out = with_caption(picture, {{{"static 15,15,15", 0}}, {{"gains", 0}, {"fused", 50}}}, 1);
    const int band = out.height - picture.height;
    EXPECT_EQ(band, 2 * (kGlyphHeight + 5) + 4);
    EXPECT_EQ(out.width, picture.width);
    EXPECT_TRUE(std::equal(picture.data.begin(), picture.data.end(),
                           out.data.begin() + std::ptrdiff_t(band) * out.width * 3));
    EXPECT_GT(ink(out, 0, 0, out.width, band), 50.0f);
}

}  // namespace
}  // namespace vkfuse::test

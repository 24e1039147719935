// Reading PNG files: every color type and bit depth libpng writes, interlacing,
// transparency, the real DIGIT background, and broken files.
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "expect_error.hpp"
#include "io/png.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

// What a test PNG holds, written by libpng exactly as given.
struct PngSpec {
    int width = 5, height = 3;
    int color_type = PNG_COLOR_TYPE_GRAY;
    int bit_depth = 8;
    bool interlace = false;
    std::vector<png_color> palette;
    std::vector<png_byte> trns;  // palette alpha, or (for gray) one transparent level
};

int samples_per_pixel(int color_type) {
    switch (color_type) {
        case PNG_COLOR_TYPE_GRAY_ALPHA: return 2;
        case PNG_COLOR_TYPE_RGB: return 3;
        case PNG_COLOR_TYPE_RGB_ALPHA: return 4;
        default: return 1;  // gray, palette index
    }
}

// The raw sample (index, gray level, color or alpha) at (y, x, s), in range for the bit depth.
unsigned sample(const PngSpec& p, int y, int x, int s) {
    unsigned range = p.color_type == PNG_COLOR_TYPE_PALETTE ? unsigned(p.palette.size()) : (1u << p.bit_depth);
    return unsigned(y * 53 + x * 29 + s * 101 + 7) * 2654435761u % range;
}

// One row packed as PNG stores it: MSB-first below 8 bits, big-endian at 16.
std::vector<png_byte> packed_row(const PngSpec& p, int y) {
    int n = samples_per_pixel(p.color_type);
    std::vector<png_byte> row((std::size_t(p.width) * n * p.bit_depth + 7) / 8);
    for (int i = 0; i < p.width * n; ++i) {
        unsigned v = sample(p, y, i / n, i % n);
        if (p.bit_depth == 16) {
            row[2 * i] = png_byte(v >> 8);
            row[2 * i + 1] = png_byte(v);
        } else {
            int bit = i * p.bit_depth;
            row[bit / 8] |= png_byte(v << (8 - p.bit_depth - bit % 8));
        }
    }
    return row;
}

// setjmp frame: nothing with a destructor lives here.
bool write_with_libpng(std::FILE* f, const PngSpec* p, png_bytepp rows) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, p->width, p->height, p->bit_depth, p->color_type,
                 p->interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (!p->palette.empty()) png_set_PLTE(png, info, p->palette.data(), int(p->palette.size()));
    png_color_16 gray_key{0, 0, 0, 0, 1};
    if (!p->trns.empty())
        png_set_tRNS(png, info, p->trns.data(), int(p->trns.size()), p->palette.empty() ? &gray_key : nullptr);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return true;
}

void write_test_png(const std::string& path, const PngSpec& p) {
    std::vector<std::vector<png_byte>> storage;
    std::vector<png_bytep> rows;
    for (int y = 0; y < p.height; ++y) storage.push_back(packed_row(p, y));
    for (auto& r : storage) rows.push_back(r.data());
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    bool ok = write_with_libpng(f, &p, rows.data());
    std::fclose(f);
    ASSERT_TRUE(ok);
}

// docs/spec.md: a sample of b bits maps to v / (2^b - 1); palette entries are 8-bit colors.
float expected(const PngSpec& p, int y, int x, int c) {
    if (p.color_type == PNG_COLOR_TYPE_PALETTE) {
        const png_color& e = p.palette[sample(p, y, x, 0)];
        return float((c == 0 ? e.red : c == 1 ? e.green : e.blue) / 255.0);
    }
    bool gray = p.color_type == PNG_COLOR_TYPE_GRAY || p.color_type == PNG_COLOR_TYPE_GRAY_ALPHA;
    return float(sample(p, y, x, gray ? 0 : c) / double((1u << p.bit_depth) - 1));
}

std::vector<png_color> test_palette(int entries) {
    std::vector<png_color> palette;
    for (int i = 0; i < entries; ++i) palette.push_back({png_byte(i * 7 + 1), png_byte(255 - i * 3), png_byte(i * 13)});
    return palette;
}

class PngFormats : public ::testing::TestWithParam<PngSpec> {};

TEST_P(PngFormats, ReadsEverySampleMapped) {
    const PngSpec& p = GetParam();
    TempDir dir;
    std::string path = dir.file("in.png");
    write_test_png(path, p);
    Image img = io::read_image(path);
    bool gray = p.color_type == PNG_COLOR_TYPE_GRAY || p.color_type == PNG_COLOR_TYPE_GRAY_ALPHA;
    ASSERT_EQ(img.height, p.height);
    ASSERT_EQ(img.width, p.width);
    ASSERT_EQ(img.channels, gray ? 1 : 3);  // alpha dropped, palette expanded
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x)
            for (int c = 0; c < img.channels; ++c)
                ASSERT_EQ(img.at(y, x, c), expected(p, y, x, c)) << "at " << y << "," << x << "," << c;
}

std::vector<PngSpec> all_formats() {
    std::vector<PngSpec> specs;
    auto add = [&](int type, int depth) {
        PngSpec p;
        p.color_type = type;
        p.bit_depth = depth;
        if (type == PNG_COLOR_TYPE_PALETTE) p.palette = test_palette(1 << std::min(depth, 5));
        specs.push_back(p);
    };
    for (int depth : {1, 2, 4, 8, 16}) add(PNG_COLOR_TYPE_GRAY, depth);
    for (int depth : {1, 2, 4, 8}) add(PNG_COLOR_TYPE_PALETTE, depth);
    for (int type : {PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA})
        for (int depth : {8, 16}) add(type, depth);
    PngSpec interlaced;  // Adam7 at an odd size that leaves some passes empty
    interlaced.color_type = PNG_COLOR_TYPE_RGB;
    interlaced.width = 13, interlaced.height = 7, interlaced.interlace = true;
    specs.push_back(interlaced);
    PngSpec one_pixel;
    one_pixel.width = one_pixel.height = 1;
    one_pixel.bit_depth = 16;
    specs.push_back(one_pixel);
    PngSpec palette_alpha;  // tRNS on a palette: alpha appears, then is dropped
    palette_alpha.color_type = PNG_COLOR_TYPE_PALETTE;
    palette_alpha.palette = test_palette(16);
    palette_alpha.trns = {0, 128, 255};
    specs.push_back(palette_alpha);
    PngSpec gray_key;  // a tRNS key on gray must not turn into a second channel
    gray_key.trns = {0};
    specs.push_back(gray_key);
    return specs;
}

std::string format_name(const ::testing::TestParamInfo<PngSpec>& info) {
    const PngSpec& p = info.param;
    return "type" + std::to_string(p.color_type) + "_depth" + std::to_string(p.bit_depth) +
           (p.interlace ? "_adam7" : "") + (p.trns.empty() ? "" : "_trns") + "_" + std::to_string(info.index);
}

INSTANTIATE_TEST_SUITE_P(AllColorTypes, PngFormats, ::testing::ValuesIn(all_formats()), format_name);

TEST(PngRead, SixteenBitSamplesAreBigEndian) {
    PngSpec p;
    p.bit_depth = 16;
    TempDir dir;
    write_test_png(dir.file("a.png"), p);
    Image img = io::read_image(dir.file("a.png"));
    EXPECT_EQ(img.at(0, 0, 0), float(sample(p, 0, 0, 0) / 65535.0));
    EXPECT_GT(sample(p, 0, 0, 0), 255u);  // a byte-swapped read would differ
}

TEST(PngRead, RealDigitBackground) {
    Image img = io::read_image(data_path("digit_bg_tacto.png"));
    EXPECT_EQ(img.height, 320);
    EXPECT_EQ(img.width, 240);
    EXPECT_EQ(img.channels, 3);
    float lo = 1, hi = 0;
    for (float v : img.data) lo = std::min(lo, v), hi = std::max(hi, v);
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_GT(hi - lo, 0.1f);  // a real frame, not a constant
}

std::string valid_png_bytes(const TempDir& dir) {
    PngSpec p;
    p.color_type = PNG_COLOR_TYPE_RGB;
    p.width = 9, p.height = 6;
    write_test_png(dir.file("good.png"), p);
    return read_bytes(dir.file("good.png"));
}

TEST(PngRead, BrokenFilesGiveFormatErrors) {
    TempDir dir;
    std::string good = valid_png_bytes(dir);
    write_bytes(dir.file("empty.png"), "");
    expect_read_error(dir.file("empty.png"), ErrorKind::Format, "empty file");
    write_bytes(dir.file("text.png"), "this is not an image at all");
    expect_read_error(dir.file("text.png"), ErrorKind::Format, "not a PNG file");
    write_bytes(dir.file("cut.png"), good.substr(0, good.size() / 2));
    expect_read_error(dir.file("cut.png"), ErrorKind::Format, "corrupt PNG");
    std::string bad_crc = good;
    bad_crc[bad_crc.size() - 20] ^= 0x55;  // inside the last IDAT
    write_bytes(dir.file("crc.png"), bad_crc);
    expect_read_error(dir.file("crc.png"), ErrorKind::Format, "corrupt PNG");
    expect_read_error(dir.file("absent.png"), ErrorKind::Io, "cannot open");
    std::filesystem::create_directory(dir.file("folder.png"));
    expect_read_error(dir.file("folder.png"), ErrorKind::Io, "not a regular file");
}

// A header claiming an enormous image in a tiny file is refused before allocating.
TEST(PngRead, ImplausibleDimensionsAreRefusedBeforeAllocation) {
    TempDir dir;
    std::string good = valid_png_bytes(dir);
    // IHDR data starts at byte 16: width, height (big-endian), then its CRC at 29.
    auto with_size = [&](std::uint32_t side) {
        std::string png = good;
        auto put32 = [&](std::size_t at, std::uint32_t v) {
            for (int i = 0; i < 4; ++i) png[at + i] = char(v >> (24 - 8 * i));
        };
        put32(16, side);
        put32(20, side);
        put32(29, std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(png.data() + 12), 17)));
        return png;
    };
    write_bytes(dir.file("big.png"), with_size(9000));  // within the size limit, but not in 100 bytes
    expect_read_error(dir.file("big.png"), ErrorKind::Format, "corrupt: header says 9000x9000 but the file has only");
    write_bytes(dir.file("huge.png"), with_size(60000));
    expect_read_error(dir.file("huge.png"), ErrorKind::Format, "image too large: 60000x60000x3");
}

TEST(PngRead, EveryTruncationIsAFormatError) {
    TempDir dir;
    std::string good = valid_png_bytes(dir);
    for (std::size_t n = 0; n < good.size(); ++n) {
        SCOPED_TRACE(n);
        write_bytes(dir.file("cut.png"), good.substr(0, n));
        expect_read_error(dir.file("cut.png"), ErrorKind::Format, "");
    }
}

TEST(PngRead, RandomDamageNeverCrashes) {
    TempDir dir;
    std::string good = valid_png_bytes(dir);
    std::mt19937 rng(11);
    for (int trial = 0; trial < 1000; ++trial) {
        std::string bad = good;
        for (int k = 0; k < 2; ++k) bad[8 + rng() % (bad.size() - 8)] = char(rng());
        write_bytes(dir.file("fuzz.png"), bad);
        try {
            Image img = io::read_image(dir.file("fuzz.png"));
            EXPECT_EQ(img.size(), img.pixels() * std::size_t(img.channels));
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(dir.file("fuzz.png") + ": ", 0), 0u) << e.what();
        }
    }
}

}  // namespace
}  // namespace vkfuse::test

namespace vkfuse::io {
namespace {

// to_8bit rounds as the 8-bit PNG writers and publishers promise:
// lround(clamp(v, 0, 1) * 255), halves away from zero, checked against that
// formula on every float whose scaled value lies within 1e-3 of a half step,
// and on the values outside [0, 1].
TEST(PngWrite, EightBitRoundingIsLroundOfTheClampedValueForEveryNearHalfFloat) {
    std::vector<float> values{-1.0f, -0.0f, 0.0f, 1.0f, 2.0f, std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min()};
    for (int k = 0; k < 255; ++k) {
        // The floats v with v * 255 in [k + 0.499, k + 0.501].
        float v = float((k + 0.499) / 255.0);
        const float end = float((k + 0.501) / 255.0);
        for (; v <= end; v = std::nextafter(v, 2.0f)) values.push_back(v);
    }
    Image image(1, int(values.size()), 1);
    image.data = values;
    const std::vector<unsigned char> got = to_8bit(image);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const auto want = static_cast<unsigned char>(std::lround(std::clamp(values[i], 0.0f, 1.0f) * 255.0));
        if (got[i] != want && ++wrong <= 5) ADD_FAILURE() << values[i] << ": " << int(got[i]) << ", want " << int(want);
    }
    EXPECT_EQ(wrong, 0u) << "of " << values.size();
    image.data = {std::numeric_limits<float>::quiet_NaN()};
    image.width = 1;
    EXPECT_EQ(to_8bit(image).front(), 0) << "NaN";
}

}  // namespace
}  // namespace vkfuse::io

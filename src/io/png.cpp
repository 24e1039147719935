// libpng reports errors by longjmp. The functions that call setjmp below hold
// nothing with a destructor, and libpng's callbacks here only copy the message
// and jump, so no C++ object is ever skipped by a longjmp. Their callers own
// the libpng structures and buffers through RAII and turn a failure into Error.
#include "io/png.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>

#include "io/io_error.hpp"
#include "io/limits.hpp"

namespace vkfuse::io {
namespace {

// Plain data shared with the libpng callbacks; safe across longjmp.
struct PngState {
    char message[200] = "";
    const unsigned char* data = nullptr;  // reading: the whole file
    std::size_t size = 0;
    std::size_t pos = 0;
};

// The header facts decode_png needs after libpng's transforms are set up.
struct PngInfo {
    png_uint_32 width = 0, height = 0;
    int channels = 0;   // after the transforms: 1..4
    int bit_depth = 0;  // after the transforms: 8 or 16
    std::size_t file_rowbytes = 0;  // one row as stored, before expansion
    std::size_t rowbytes = 0;       // one row as decoded
};

[[noreturn]] void on_error(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngState*>(png_get_error_ptr(png));
    std::snprintf(state->message, sizeof state->message, "%s", message);
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // libpng recovers from these by itself

void read_from_memory(png_structp png, png_bytep out, png_size_t count) {
    auto* state = static_cast<PngState*>(png_get_io_ptr(png));
    if (count > state->size - state->pos) png_error(png, "truncated");
    std::memcpy(out, state->data + state->pos, count);
    state->pos += count;
}

// Header and transforms: everything is turned into 8- or 16-bit gray or RGB
// (possibly still with an alpha channel, which the copy below skips).
bool read_header(png_structp png, png_infop info, PngState* state, PngInfo* out) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_read_fn(png, state, read_from_memory);
    png_read_info(png, info);
    out->file_rowbytes = png_get_rowbytes(png, info);
    int color_type = png_get_color_type(png, info);
    if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (color_type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
    png_set_strip_alpha(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    out->width = png_get_image_width(png, info);
    out->height = png_get_image_height(png, info);
    out->channels = png_get_channels(png, info);
    out->bit_depth = png_get_bit_depth(png, info);
    out->rowbytes = png_get_rowbytes(png, info);
    return true;
}

bool read_rows(png_structp png, png_infop info, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_image(png, rows);
    png_read_end(png, info);  // checks the rest of the file, down to IEND
    return true;
}

bool write_rows(png_structp png, png_infop info, std::FILE* out, const PngInfo* shape, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, out);
    int color_type = shape->channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB;
    png_set_IHDR(png, info, shape->width, shape->height, 8, color_type, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    return true;
}

// Owns libpng's read or write structures.
class PngHandle {
public:
    PngHandle(bool reading, PngState* state) : reading_(reading) {
        png_ = reading ? png_create_read_struct(PNG_LIBPNG_VER_STRING, state, on_error, on_warning)
                       : png_create_write_struct(PNG_LIBPNG_VER_STRING, state, on_error, on_warning);
        if (png_) info_ = png_create_info_struct(png_);
        if (!png_ || !info_) {
            destroy();
            throw std::bad_alloc();
        }
    }
    ~PngHandle() { destroy(); }
    PngHandle(const PngHandle&) = delete;
    PngHandle& operator=(const PngHandle&) = delete;
    png_structp png() const { return png_; }
    png_infop info() const { return info_; }

private:
    void destroy() {
        if (reading_) png_destroy_read_struct(&png_, info_ ? &info_ : nullptr, nullptr);
        else png_destroy_write_struct(&png_, info_ ? &info_ : nullptr);
    }
    bool reading_;
    png_structp png_ = nullptr;
    png_infop info_ = nullptr;
};

// Deflate expands at most 1032:1, so a file too small for the rows its header
// declares is corrupt; refusing it here avoids allocating for a lie.
void check_plausible(const PngInfo& info, std::size_t file_size, const std::string& path) {
    check_image_size(path, info.height, info.width, std::uint64_t(info.channels));
    std::uint64_t stored = std::uint64_t(info.height) * (info.file_rowbytes + 1);
    if (stored / 1032 > file_size)
        fail(ErrorKind::Format, path,
             "corrupt: header says " + std::to_string(info.height) + "x" + std::to_string(info.width) +
                 " but the file has only " + std::to_string(file_size) + " bytes");
}

// Decoded rows (8- or 16-bit big-endian, 1..4 channels) to float, v / (2^bits - 1).
Image to_image(const std::vector<unsigned char>& pixels, const PngInfo& info) {
    int out_channels = info.channels >= 3 ? 3 : 1;
    Image image(int(info.height), int(info.width), out_channels);
    const int bytes = info.bit_depth / 8;
    const double max_value = bytes == 2 ? 65535.0 : 255.0;
    for (int y = 0; y < image.height; ++y) {
        const unsigned char* row = pixels.data() + std::size_t(y) * info.rowbytes;
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < out_channels; ++c) {
                const unsigned char* p = row + (std::size_t(x) * info.channels + c) * bytes;
                unsigned v = bytes == 2 ? (unsigned(p[0]) << 8) | p[1] : p[0];
                image.at(y, x, c) = float(v / max_value);
            }
    }
    return image;
}

std::vector<unsigned char> quantize(const Image& image) {
    std::vector<unsigned char> out(image.size());
    std::transform(image.data.begin(), image.data.end(), out.begin(),
                   [](float v) { return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0)); });
    return out;
}

std::vector<png_bytep> row_pointers(unsigned char* pixels, std::size_t height, std::size_t rowbytes) {
    std::vector<png_bytep> rows(height);
    for (std::size_t y = 0; y < height; ++y) rows[y] = pixels + y * rowbytes;
    return rows;
}

}  // namespace

Image decode_png(const std::vector<unsigned char>& file, const std::string& path) {
    if (file.empty()) fail(ErrorKind::Format, path, "empty file");
    if (file.size() < 8 || png_sig_cmp(file.data(), 0, 8) != 0) fail(ErrorKind::Format, path, "not a PNG file");
    PngState state;
    state.data = file.data();
    state.size = file.size();
    PngHandle handle(true, &state);
    PngInfo info;
    if (!read_header(handle.png(), handle.info(), &state, &info))
        fail(ErrorKind::Format, path, std::string("corrupt PNG: ") + state.message);
    check_plausible(info, file.size(), path);
    std::vector<unsigned char> pixels(std::size_t(info.height) * info.rowbytes);
    std::vector<png_bytep> rows = row_pointers(pixels.data(), info.height, info.rowbytes);
    if (!read_rows(handle.png(), handle.info(), rows.data()))
        fail(ErrorKind::Format, path, std::string("corrupt PNG: ") + state.message);
    return to_image(pixels, info);
}

void write_png(std::FILE* out, const Image& image, const std::string& path) {
    std::vector<unsigned char> pixels = quantize(image);
    PngInfo shape;
    shape.width = png_uint_32(image.width);
    shape.height = png_uint_32(image.height);
    shape.channels = image.channels;
    std::vector<png_bytep> rows =
        row_pointers(pixels.data(), std::size_t(image.height), std::size_t(image.width) * image.channels);
    PngState state;
    PngHandle handle(false, &state);
    if (!write_rows(handle.png(), handle.info(), out, &shape, rows.data()))
        fail(ErrorKind::Io, path, std::string("cannot write PNG: ") + state.message);
}

}  // namespace vkfuse::io

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
#include <optional>

#include "io/file_bytes.hpp"
#include "io/io_error.hpp"
#include "io/limits.hpp"

namespace vkfuse::io {
namespace {

// Plain data shared with the libpng callbacks; safe across longjmp. Bytes
// come from memory (data, size) or from file, never more than budget of them:
// a PNG's compressed stream is not bounded by its header, so the reader caps
// what it reads (see read_budget) instead of following a huge file to its end.
struct PngState {
    char message[200] = "";
    const unsigned char* data = nullptr;  // reading from memory: the whole file
    InputFile* file = nullptr;            // or from a file, through a buffer
    std::uint64_t size = 0;               // the file's size
    std::uint64_t pos = 0;                // bytes handed to libpng so far
    std::uint64_t budget = 0;             // at most this many
    unsigned char* buffer = nullptr;      // file reads, kBufferBytes
    std::size_t buffered = 0, buffer_pos = 0;
    char io_error[200] = "";              // a failed read(2), reported as Error(Io)
};

constexpr std::size_t kBufferBytes = 64 * 1024;

// The header facts decode_png needs after libpng's transforms are set up.
struct PngInfo {
    png_uint_32 width = 0, height = 0;
    int channels = 0;   // after the transforms: 1..4
    int bit_depth = 0;  // after the transforms: 8 or 16
    std::size_t file_rowbytes = 0;  // one row as stored, before expansion
    std::size_t rowbytes = 0;       // one row as decoded
    bool interlaced = false;
};

[[noreturn]] void on_error(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngState*>(png_get_error_ptr(png));
    std::snprintf(state->message, sizeof state->message, "%s", message);
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // libpng recovers from these by itself

// Copies count bytes from the file or memory; png_error ends the decode when
// the file ends or the budget is spent (libpng then reports "corrupt PNG").
void read_bytes(png_structp png, png_bytep out, png_size_t count) {
    auto* state = static_cast<PngState*>(png_get_io_ptr(png));
    if (count > state->size - state->pos) png_error(png, "truncated");
    if (count > state->budget - state->pos) png_error(png, "more chunk data than an image of this size can hold");
    if (state->data) {
        std::memcpy(out, state->data + state->pos, count);
        state->pos += count;
        return;
    }
    while (count > 0) {
        if (state->buffer_pos == state->buffered) {
            // Never past the budget: what lies beyond is not read at all.
            const std::size_t ask = std::size_t(std::min<std::uint64_t>(kBufferBytes, state->budget - state->pos));
            std::size_t got = 0;
            try {
                got = state->file->read_some(state->buffer, ask);
            } catch (const Error& e) {
                std::snprintf(state->io_error, sizeof state->io_error, "%s", e.what());
            }
            if (got == 0) png_error(png, state->io_error[0] ? "read error" : "truncated");
            state->buffered = got;
            state->buffer_pos = 0;
        }
        const std::size_t n = std::min(count, state->buffered - state->buffer_pos);
        std::memcpy(out, state->buffer + state->buffer_pos, n);
        state->buffer_pos += n;
        state->pos += n;
        out += n;
        count -= n;
    }
}

// Header and transforms: everything is turned into 8- or 16-bit gray or RGB
// (possibly still with an alpha channel, which the copy below skips).
bool read_header(png_structp png, png_infop info, PngState* state, PngInfo* out) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_read_fn(png, state, read_bytes);
    png_set_sig_bytes(png, 8);  // checked (and consumed) by the caller
    png_read_info(png, info);
    out->file_rowbytes = png_get_rowbytes(png, info);
    out->interlaced = png_get_interlace_type(png, info) != PNG_INTERLACE_NONE;
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

// Where decoded rows go: float samples of an image of the header's size.
struct RowSink {
    float* data;
    const PngInfo* info;
};

// One decoded row (8- or 16-bit big-endian, 1..4 channels) to float, v / (2^bits - 1).
void convert_row(const unsigned char* row, std::size_t y, const RowSink* sink) {
    const PngInfo& info = *sink->info;
    const int out_channels = info.channels >= 3 ? 3 : 1;
    const int bytes = info.bit_depth / 8;
    const double max_value = bytes == 2 ? 65535.0 : 255.0;
    float* out = sink->data + y * info.width * std::size_t(out_channels);
    for (std::size_t x = 0; x < info.width; ++x)
        for (int c = 0; c < out_channels; ++c) {
            const unsigned char* p = row + (x * std::size_t(info.channels) + std::size_t(c)) * std::size_t(bytes);
            const unsigned v = bytes == 2 ? (unsigned(p[0]) << 8) | p[1] : p[0];
            *out++ = float(v / max_value);
        }
}

// Non-interlaced: one row buffer, each row converted as it is decoded.
bool read_rows_streaming(png_structp png, png_infop info, unsigned char* row, const RowSink* sink) {
    if (setjmp(png_jmpbuf(png))) return false;
    for (std::size_t y = 0; y < sink->info->height; ++y) {
        png_read_row(png, row, nullptr);
        convert_row(row, y, sink);
    }
    png_read_end(png, info);  // checks the rest of the file, down to IEND
    return true;
}

// Interlaced: the passes fill every row several times, so all rows are kept.
bool read_rows(png_structp png, png_infop info, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_image(png, rows);
    png_read_end(png, info);
    return true;
}

bool write_rows(png_structp png, png_infop info, std::FILE* out, const PngInfo* shape, png_bytepp rows, bool fast) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, out);
    if (fast) {
        png_set_compression_level(png, 1);
        png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    }
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

std::vector<png_bytep> row_pointers(unsigned char* pixels, std::size_t height, std::size_t rowbytes) {
    std::vector<png_bytep> rows(height);
    for (std::size_t y = 0; y < height; ++y) rows[y] = pixels + y * rowbytes;
    return rows;
}

// Deflate expands at most 1032:1, so a file too small for the rows its header
// declares is corrupt; refusing it here avoids allocating for a lie.
void check_plausible(const PngInfo& info, std::uint64_t file_size, const std::string& path) {
    check_image_size(path, info.height, info.width, std::uint64_t(info.channels));
    std::uint64_t stored = std::uint64_t(info.height) * (info.file_rowbytes + 1);
    if (stored / 1032 > file_size)
        fail(ErrorKind::Format, path,
             "corrupt: header says " + std::to_string(info.height) + "x" + std::to_string(info.width) +
                 " but the file has only " + std::to_string(file_size) + " bytes");
}

// Chunks before the image data (a colour profile, text) may take this much.
constexpr std::uint64_t kMetadataBytes = std::uint64_t(64) << 20;

// The most bytes a decode of this image reads: the rows as stored (filter
// byte included) even if deflate did not compress them at all, twice over
// for stored-block and chunk overheads, plus the metadata allowance. A real
// encoder stays far below; a 1 TB file behind a small header is not read.
std::uint64_t read_budget(const PngInfo& info) {
    return 2 * std::uint64_t(info.height) * (info.file_rowbytes + 1) + 2 * kMetadataBytes;
}

// One decode from memory or from a file: the signature, the header (checked
// against the file's size before anything is allocated for pixels), the rows.
class PngReader {
public:
    PngReader(const unsigned char* data, std::uint64_t size, InputFile* file, const std::string& path)
        : path_(path) {
        state_.data = data;
        state_.file = file;
        state_.size = size;
        state_.budget = kMetadataBytes + 8;
        if (size == 0) fail(ErrorKind::Format, path, "empty file");
        unsigned char signature[8] = {};
        if (file) {
            buffer_.resize(kBufferBytes);
            state_.buffer = buffer_.data();
            if (size >= 8) file->read_exact(signature, 8);
        } else if (size >= 8) {
            std::memcpy(signature, data, 8);
        }
        if (size < 8 || png_sig_cmp(signature, 0, 8) != 0) fail(ErrorKind::Format, path, "not a PNG file");
        state_.pos = 8;
        handle_.emplace(true, &state_);
        if (!read_header(handle_->png(), handle_->info(), &state_, &info_)) corrupt();
        check_plausible(info_, size, path);
        state_.budget = state_.pos + read_budget(info_);
    }

    const PngInfo& info() const { return info_; }

    Image image() {
        const int out_channels = info_.channels >= 3 ? 3 : 1;
        Image image(int(info_.height), int(info_.width), out_channels);
        const RowSink sink{image.data.data(), &info_};
        if (!info_.interlaced) {
            std::vector<unsigned char> row(info_.rowbytes);
            if (!read_rows_streaming(handle_->png(), handle_->info(), row.data(), &sink)) corrupt();
            return image;
        }
        std::vector<unsigned char> pixels(std::size_t(info_.height) * info_.rowbytes);
        std::vector<png_bytep> rows = row_pointers(pixels.data(), info_.height, info_.rowbytes);
        if (!read_rows(handle_->png(), handle_->info(), rows.data())) corrupt();
        for (std::size_t y = 0; y < info_.height; ++y) convert_row(rows[y], y, &sink);
        return image;
    }

private:
    [[noreturn]] void corrupt() const {
        if (state_.io_error[0]) throw Error(ErrorKind::Io, state_.io_error);
        fail(ErrorKind::Format, path_, std::string("corrupt PNG: ") + state_.message);
    }

    const std::string& path_;
    PngState state_;
    std::vector<unsigned char> buffer_;
    std::optional<PngHandle> handle_;
    PngInfo info_;
};

}  // namespace

// round(clamp(v, 0, 1) * 255), halves away from zero, NaN to 0. A float
// times 255 is exact in a double and so is that plus 0.5, so truncating it
// rounds exactly as lround would, without lround's call per value (the cost
// of publishing every fused image of a rig).
std::vector<unsigned char> to_8bit(const Image& image) {
    std::vector<unsigned char> out(image.size());
    std::transform(image.data.begin(), image.data.end(), out.begin(), [](float v) {
        const float c = std::max(0.0f, std::min(v, 1.0f));
        return static_cast<unsigned char>(static_cast<int>(double(c) * 255.0 + 0.5));
    });
    return out;
}

Image decode_png(const std::vector<unsigned char>& file, const std::string& path) {
    return PngReader(file.data(), file.size(), nullptr, path).image();
}

ImageHeader read_png_header(InputFile& file) {
    PngReader reader(nullptr, file.size(), &file, file.path());
    const PngInfo& info = reader.info();
    ImageHeader header;
    header.height = int(info.height);
    header.width = int(info.width);
    header.channels = info.channels >= 3 ? 3 : 1;
    header.decode_bytes = kBufferBytes + (info.interlaced ? std::uint64_t(info.height) * (info.rowbytes + sizeof(png_bytep))
                                                         : std::uint64_t(info.rowbytes));
    return header;
}

Image read_png(InputFile& file) { return PngReader(nullptr, file.size(), &file, file.path()).image(); }

void write_png(std::FILE* out, const Image& image, const std::string& path, PngSpeed speed) {
    std::vector<unsigned char> pixels = to_8bit(image);
    PngInfo shape;
    shape.width = png_uint_32(image.width);
    shape.height = png_uint_32(image.height);
    shape.channels = image.channels;
    std::vector<png_bytep> rows =
        row_pointers(pixels.data(), std::size_t(image.height), std::size_t(image.width) * image.channels);
    PngState state;
    PngHandle handle(false, &state);
    if (!write_rows(handle.png(), handle.info(), out, &shape, rows.data(), speed == PngSpeed::Fast))
        fail(ErrorKind::Io, path, std::string("cannot write PNG: ") + state.message);
}

}  // namespace vkfuse::io

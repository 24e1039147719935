#include "io/npy.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include "io/atomic_write.hpp"
#include "io/file_bytes.hpp"
#include "io/io_error.hpp"
#include "io/limits.hpp"
#include "io/npy_header.hpp"

namespace vkfuse::io {
namespace {

// Where sample (y, x, c) lies in the file, in elements.
struct Layout {
    int height = 0, width = 0, channels = 0;  // channels as stored (1, 3 or 4)
    std::size_t stride_y = 0, stride_x = 0, stride_c = 0;
};

std::string shape_text(const std::vector<std::uint64_t>& shape) {
    std::string s;
    for (std::uint64_t d : shape) s += (s.empty() ? "" : "x") + std::to_string(d);
    return s.empty() ? "()" : s;
}

Layout layout_of(const NpyHeader& header, const std::string& path) {
    const auto& shape = header.shape;
    bool rank_ok = shape.size() == 2 || shape.size() == 3;
    std::uint64_t channels = shape.size() == 3 ? shape[2] : 1;
    if (!rank_ok || !(channels == 1 || channels == 3 || channels == 4))
        fail(ErrorKind::Format, path,
             "unsupported shape " + shape_text(shape) + " (expected HxW or HxWxC with C = 1, 3 or 4)");
    check_image_size(path, shape[0], shape[1], channels);
    Layout l{int(shape[0]), int(shape[1]), int(channels)};
    // C order: the last axis varies fastest; Fortran order: the first.
    if (header.fortran_order) {
        l.stride_y = 1;
        l.stride_x = std::size_t(l.height);
        l.stride_c = std::size_t(l.height) * l.width;
    } else {
        l.stride_c = 1;
        l.stride_x = std::size_t(l.channels);
        l.stride_y = std::size_t(l.width) * l.channels;
    }
    return l;
}

std::uint64_t data_bytes(const NpyHeader& header, const Layout& l) {
    return std::uint64_t(l.height) * std::uint64_t(l.width) * std::uint64_t(l.channels) * item_size(header.kind);
}

// The file holds the header and exactly the data it declares: a shorter file
// is truncated, a longer one corrupt (and never read past the data).
void check_data_size(const NpyHeader& header, const Layout& l, std::uint64_t available, const std::string& path) {
    const std::uint64_t needed = data_bytes(header, l);
    if (available == needed) return;
    std::string says = "header says " + shape_text(header.shape) + " " + std::string(type_name(header.kind)) +
                       " (" + std::to_string(needed) + " bytes)";
    fail(ErrorKind::Format, path,
         std::string(available < needed ? "truncated: " : "corrupt: ") + says + " but the file has " +
             std::to_string(available));
}

template <class T>
T load(const unsigned char* p, bool swap) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, p, sizeof(T));
    if (swap) std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
}

// Converts the kept samples of rows [y0, y1); data points at the element
// (y0, 0, 0) in C order, at (0, 0, 0) in Fortran order (where y0 = 0).
template <class T>
void convert(const unsigned char* data, const Layout& l, bool swap, double divisor, int y0, int y1, Image& out) {
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < out.channels; ++c) {
                std::size_t i = std::size_t(y - y0) * l.stride_y + x * l.stride_x + c * l.stride_c;
                out.at(y, x, c) = float(double(load<T>(data + i * sizeof(T), swap)) / divisor);
            }
}

void convert_rows(const NpyHeader& header, const unsigned char* data, const Layout& l, int y0, int y1, Image& out) {
    bool swap = header.big_endian != (std::endian::native == std::endian::big);
    switch (header.kind) {
        case NpyKind::F4: convert<float>(data, l, swap, 1.0, y0, y1, out); break;
        case NpyKind::F8: convert<double>(data, l, swap, 1.0, y0, y1, out); break;
        case NpyKind::U1: convert<std::uint8_t>(data, l, swap, 255.0, y0, y1, out); break;
        case NpyKind::U2: convert<std::uint16_t>(data, l, swap, 65535.0, y0, y1, out); break;
    }
}

// Rows read per chunk in C order: about 4 MiB, at least one row.
constexpr std::uint64_t kChunkBytes = std::uint64_t(4) << 20;

std::uint64_t row_bytes(const NpyHeader& header, const Layout& l) {
    return std::uint64_t(l.width) * std::uint64_t(l.channels) * item_size(header.kind);
}

int rows_per_chunk(const NpyHeader& header, const Layout& l) {
    return int(std::clamp<std::uint64_t>(kChunkBytes / row_bytes(header, l), 1, std::uint64_t(l.height)));
}

// The header of an open file, from its first bytes only, with the data size
// checked against the file's size.
struct Checked {
    NpyHeader header;
    Layout layout;
};

Checked read_checked_header(InputFile& file) {
    unsigned char prefix[12];
    const std::size_t got = file.read_some(prefix, std::min<std::uint64_t>(file.size(), sizeof prefix));
    const std::size_t total = npy_header_size(prefix, got, file.size(), file.path());
    std::vector<unsigned char> head(prefix, prefix + got);
    if (total > got) {
        head.resize(total);
        file.read_exact(head.data() + got, total - got);
    }
    Checked c{parse_npy_header(head.data(), head.size(), file.size(), file.path()), {}};
    c.layout = layout_of(c.header, file.path());
    check_data_size(c.header, c.layout, file.size() - c.header.data_offset, file.path());
    return c;
}

void put_float_le(float v, unsigned char* out) {
    std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
    for (int i = 0; i < 4; ++i) out[i] = static_cast<unsigned char>(bits >> (8 * i));
}

}  // namespace

Image decode_npy(const std::vector<unsigned char>& file, const std::string& path) {
    NpyHeader header = parse_npy_header(file, path);
    Layout layout = layout_of(header, path);
    check_data_size(header, layout, file.size() - header.data_offset, path);
    Image image(layout.height, layout.width, layout.channels == 1 ? 1 : 3);
    convert_rows(header, file.data() + header.data_offset, layout, 0, layout.height, image);
    return image;
}

ImageHeader read_npy_header(InputFile& file) {
    const Checked c = read_checked_header(file);
    ImageHeader h;
    h.height = c.layout.height;
    h.width = c.layout.width;
    h.channels = c.layout.channels == 1 ? 1 : 3;
    h.decode_bytes = c.header.data_offset + (c.header.fortran_order
                                                 ? data_bytes(c.header, c.layout)
                                                 : rows_per_chunk(c.header, c.layout) * row_bytes(c.header, c.layout));
    return h;
}

Image read_npy(InputFile& file) {
    const Checked c = read_checked_header(file);
    const Layout& l = c.layout;
    Image image(l.height, l.width, l.channels == 1 ? 1 : 3);
    if (c.header.fortran_order) {  // the first axis varies fastest: every row is spread over the file
        const std::vector<unsigned char> data = file.read_exact(std::size_t(data_bytes(c.header, l)));
        convert_rows(c.header, data.data(), l, 0, l.height, image);
        return image;
    }
    const int chunk = rows_per_chunk(c.header, l);
    std::vector<unsigned char> data(std::size_t(chunk * row_bytes(c.header, l)));
    for (int y = 0; y < l.height; y += chunk) {
        const int rows = std::min(chunk, l.height - y);
        file.read_exact(data.data(), std::size_t(rows * row_bytes(c.header, l)));
        convert_rows(c.header, data.data(), l, y, y + rows, image);
    }
    return image;
}

void write_npy(std::FILE* out, const Image& image, const std::string& path) {
    std::vector<std::uint64_t> shape{std::uint64_t(image.height), std::uint64_t(image.width)};
    if (image.channels != 1) shape.push_back(std::uint64_t(image.channels));
    std::string header = format_npy_header(shape);
    std::vector<unsigned char> bytes(header.begin(), header.end());
    bytes.resize(header.size() + image.size() * 4);
    for (std::size_t i = 0; i < image.size(); ++i) put_float_le(image.data[i], bytes.data() + header.size() + 4 * i);
    write_all(out, bytes.data(), bytes.size(), path);
}

}  // namespace vkfuse::io

#include "io/npy.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstring>

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

void check_data_size(const NpyHeader& header, const Layout& l, std::size_t available, const std::string& path) {
    std::size_t needed = std::size_t(l.height) * l.width * l.channels * item_size(header.kind);
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

// Converts every kept sample; integers map to [0, 1] by dividing by their maximum.
template <class T>
void convert(const unsigned char* data, const Layout& l, bool swap, double divisor, Image& out) {
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < out.channels; ++c) {
                std::size_t i = y * l.stride_y + x * l.stride_x + c * l.stride_c;
                out.at(y, x, c) = float(double(load<T>(data + i * sizeof(T), swap)) / divisor);
            }
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
    const unsigned char* data = file.data() + header.data_offset;
    bool swap = header.big_endian != (std::endian::native == std::endian::big);
    Image image(layout.height, layout.width, layout.channels == 1 ? 1 : 3);
    switch (header.kind) {
        case NpyKind::F4: convert<float>(data, layout, swap, 1.0, image); break;
        case NpyKind::F8: convert<double>(data, layout, swap, 1.0, image); break;
        case NpyKind::U1: convert<std::uint8_t>(data, layout, swap, 255.0, image); break;
        case NpyKind::U2: convert<std::uint16_t>(data, layout, swap, 65535.0, image); break;
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
    if (std::fwrite(bytes.data(), 1, bytes.size(), out) != bytes.size())
        fail(ErrorKind::Io, path, "cannot write: " + system_message(errno));
}

}  // namespace vkfuse::io

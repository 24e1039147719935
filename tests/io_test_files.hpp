// io_test_files.hpp - files that lie about their size, and the checks the
// I/O safety tests share (test_io_limits.cpp, test_io_atomic.cpp,
// test_cli_io_safety.cpp). Header-only.
#pragma once
#include <sys/stat.h>
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "npy_bytes.hpp"
#include "temp_dir.hpp"

namespace vkfuse::test {

// The process umask set to mask for one scope (tests of output modes).
class Umask {
public:
    explicit Umask(mode_t mask) : old_(::umask(mask)) {}
    ~Umask() { ::umask(old_); }
    Umask(const Umask&) = delete;
    Umask& operator=(const Umask&) = delete;

private:
    mode_t old_;
};

inline constexpr std::uint64_t kTerabyte = std::uint64_t(1) << 40;

inline std::string be32(std::uint32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[std::size_t(i)] = char(v >> (24 - 8 * i));
    return s;
}

inline std::string png_chunk(const std::string& type, const std::string& data) {
    const std::string body = type + data;
    const auto crc = std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size())));
    return be32(std::uint32_t(data.size())) + body + be32(crc);
}

inline std::string png_signature() { return std::string("\x89PNG\r\n\x1a\n", 8); }

inline std::string ihdr(std::uint32_t width, std::uint32_t height, int bit_depth = 8, int color_type = 0) {
    return png_chunk("IHDR", be32(width) + be32(height) + char(bit_depth) + char(color_type) + '\0' + '\0' + '\0');
}

// A valid w x h 8-bit gray PNG of zeros, compressed by zlib.
inline std::string zero_png(std::uint32_t width, std::uint32_t height) {
    const std::string raw(std::size_t(height) * (width + 1), '\0');
    uLongf size = compressBound(uLong(raw.size()));
    std::string packed(size, '\0');
    compress2(reinterpret_cast<Bytef*>(packed.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
              uLong(raw.size()), 9);
    packed.resize(size);
    return png_signature() + ihdr(width, height) + png_chunk("IDAT", packed) + png_chunk("IEND", "");
}

// A PNG header claiming side x side gray pixels, with an IDAT of idat_bytes
// zeros (not valid deflate): large enough for the plausibility check (deflate
// expands at most 1032:1), never decodable. What is refused before decoding
// must be refused from the header alone.
inline std::string fake_huge_png(std::uint32_t side, std::size_t idat_bytes) {
    return png_signature() + ihdr(side, side) + png_chunk("IDAT", std::string(idat_bytes, '\0')) +
           png_chunk("IEND", "");
}

// A valid .npy header for float32 h x w x c data, without the data.
inline std::string npy_header_only(int h, int w, int c) {
    return npy_bytes(dict_of("<f4", false,
                             "(" + std::to_string(h) + ", " + std::to_string(w) + ", " + std::to_string(c) + ")"),
                     "");
}

// bytes, then a hole up to size: a sparse file costing one block on disk.
inline void write_sparse(const std::string& path, const std::string& bytes, std::uint64_t size) {
    write_bytes(path, bytes);
    std::filesystem::resize_file(path, size);
}

inline unsigned mode_of(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return 0;
    return unsigned(st.st_mode & 07777);
}

// RFC 3629 UTF-8: what every JSON text must be.
inline bool valid_utf8(std::string_view s) {
    for (std::size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        std::size_t n = c < 0x80 ? 1 : c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
        if (n == 0 || s.size() - i < n) return false;
        if (n > 1) {
            const auto c1 = static_cast<unsigned char>(s[i + 1]);
            const unsigned char lo = c == 0xE0 ? 0xA0 : c == 0xF0 ? 0x90 : 0x80;
            const unsigned char hi = c == 0xED ? 0x9F : c == 0xF4 ? 0x8F : 0xBF;
            if (c1 < lo || c1 > hi) return false;
            for (std::size_t k = 2; k < n; ++k)
                if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return false;
        }
        i += n;
    }
    return true;
}

}  // namespace vkfuse::test

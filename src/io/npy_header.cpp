#include "io/npy_header.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstring>
#include <optional>

#include "io/io_error.hpp"

namespace vkfuse::io {
namespace {

constexpr unsigned char kMagic[] = {0x93, 'N', 'U', 'M', 'P', 'Y'};

// A recursive-descent reader for the one Python literal NumPy writes:
// {'descr': '<f4', 'fortran_order': False, 'shape': (3, 4), }
// It never reads past the end of its text and fails with a message naming path.
class DictReader {
public:
    DictReader(std::string_view text, const std::string& path) : text_(text), path_(path) {}

    NpyHeader read() {
        NpyHeader header;
        bool seen_descr = false, seen_order = false, seen_shape = false;
        expect('{');
        while (!try_take('}')) {
            std::string key = string();
            expect(':');
            if (key == "descr" && !seen_descr) {
                seen_descr = true;
                parse_descr(string(), header);
            } else if (key == "fortran_order" && !seen_order) {
                seen_order = true;
                header.fortran_order = boolean();
            } else if (key == "shape" && !seen_shape) {
                seen_shape = true;
                header.shape = tuple();
            } else {
                bad("unexpected or repeated key '" + key + "'");
            }
            if (!try_take(',')) {
                expect('}');
                break;
            }
        }
        if (!seen_descr || !seen_order || !seen_shape) bad("missing 'descr', 'fortran_order' or 'shape'");
        return header;
    }

private:
    [[noreturn]] void bad(const std::string& problem) const {
        fail(ErrorKind::Format, path_, "corrupt .npy header: " + problem);
    }

    void skip_space() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }
    bool try_take(char c) {
        skip_space();
        return take_word(std::string_view(&c, 1));
    }
    bool take_word(std::string_view word) {
        if (text_.substr(pos_, word.size()) != word) return false;
        pos_ += word.size();
        return true;
    }
    void expect(char c) {
        if (!try_take(c)) bad(std::string("expected '") + c + "'");
    }
    std::string string() {
        skip_space();
        if (pos_ >= text_.size() || (text_[pos_] != '\'' && text_[pos_] != '"')) bad("expected a quoted string");
        char quote = text_[pos_++];
        std::size_t end = text_.find(quote, pos_);
        if (end == std::string_view::npos) bad("unterminated string");
        std::string s(text_.substr(pos_, end - pos_));
        pos_ = end + 1;
        return s;
    }
    bool boolean() {
        skip_space();
        if (take_word("True")) return true;
        if (take_word("False")) return false;
        bad("expected True or False");
    }
    std::uint64_t integer() {
        skip_space();
        std::size_t start = pos_;
        std::uint64_t value = 0;
        while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) {
            if (value > (UINT64_MAX - 9) / 10) bad("dimension out of range");
            value = value * 10 + std::uint64_t(text_[pos_++] - '0');
        }
        if (pos_ == start) bad("expected a non-negative integer in 'shape'");
        try_take('L');  // Python 2 long literals, as old NumPy wrote them
        return value;
    }
    std::vector<std::uint64_t> tuple() {
        std::vector<std::uint64_t> dims;
        expect('(');
        while (!try_take(')')) {
            if (dims.size() >= 32) bad("too many dimensions");
            dims.push_back(integer());
            if (!try_take(',')) {
                expect(')');
                break;
            }
        }
        return dims;
    }
    void parse_descr(const std::string& descr, NpyHeader& header) const {
        auto kind = descr.size() == 3 ? kind_of(descr.substr(1)) : std::nullopt;
        char order = descr.empty() ? '?' : descr[0];
        bool one_byte = kind == NpyKind::U1;
        if (!kind || !(order == '<' || order == '>' || order == '=' || (order == '|' && one_byte)))
            fail(ErrorKind::Format, path_,
                 "unsupported dtype '" + descr + "' (expected float32, float64, uint8 or uint16)");
        header.kind = *kind;
        // '=' is native order; NumPy writes it as '<' or '>', but accept it as the host's.
        header.big_endian = order == '>' || (order == '=' && std::endian::native == std::endian::big);
    }
    static std::optional<NpyKind> kind_of(const std::string& code) {
        if (code == "f4") return NpyKind::F4;
        if (code == "f8") return NpyKind::F8;
        if (code == "u1") return NpyKind::U1;
        if (code == "u2") return NpyKind::U2;
        return std::nullopt;
    }

    std::string_view text_;
    const std::string& path_;
    std::size_t pos_ = 0;
};

std::uint32_t little_endian(const unsigned char* p, int bytes) {
    std::uint32_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}

}  // namespace

std::size_t item_size(NpyKind kind) {
    switch (kind) {
        case NpyKind::F4: return 4;
        case NpyKind::F8: return 8;
        case NpyKind::U1: return 1;
        case NpyKind::U2: return 2;
    }
    return 0;
}

std::string_view type_name(NpyKind kind) {
    switch (kind) {
        case NpyKind::F4: return "float32";
        case NpyKind::F8: return "float64";
        case NpyKind::U1: return "uint8";
        case NpyKind::U2: return "uint16";
    }
    return "?";
}

std::size_t npy_header_size(const unsigned char* prefix, std::size_t prefix_size, std::uint64_t file_size,
                            const std::string& path) {
    if (file_size == 0) fail(ErrorKind::Format, path, "empty file");
    if (prefix_size < 10 || std::memcmp(prefix, kMagic, sizeof kMagic) != 0)
        fail(ErrorKind::Format, path, "not a .npy file");
    int major = prefix[6], minor = prefix[7];
    if (major < 1 || major > 3 || minor != 0)
        fail(ErrorKind::Format, path,
             "unsupported .npy version " + std::to_string(major) + "." + std::to_string(minor));
    // Version 1.0 stores the header length in 2 bytes, 2.0 and 3.0 in 4.
    std::size_t length_bytes = major == 1 ? 2 : 4;
    if (prefix_size < 8 + length_bytes) fail(ErrorKind::Format, path, "truncated .npy header");
    std::uint64_t header_length = little_endian(prefix + 8, int(length_bytes));
    std::size_t offset = 8 + length_bytes;
    if (header_length > file_size - offset)
        fail(ErrorKind::Format, path,
             "truncated .npy header: it claims " + std::to_string(header_length) + " bytes but the file has " +
                 std::to_string(file_size - offset));
    if (header_length > kMaxNpyHeaderBytes)
        fail(ErrorKind::Format, path,
             "corrupt .npy header: it claims " + std::to_string(header_length) + " bytes, more than the " +
                 std::to_string(kMaxNpyHeaderBytes) + " a header of float or integer images takes");
    return offset + std::size_t(header_length);
}

NpyHeader parse_npy_header(const unsigned char* data, std::size_t size, std::uint64_t file_size,
                           const std::string& path) {
    const std::size_t total = npy_header_size(data, std::min<std::size_t>(size, 12), file_size, path);
    if (size < total) fail(ErrorKind::Format, path, "truncated .npy header");
    const std::size_t offset = data[6] == 1 ? 10 : 12;
    std::string_view text(reinterpret_cast<const char*>(data) + offset, total - offset);
    NpyHeader header = DictReader(text, path).read();
    header.data_offset = total;
    return header;
}

NpyHeader parse_npy_header(const std::vector<unsigned char>& file, const std::string& path) {
    return parse_npy_header(file.data(), file.size(), file.size(), path);
}

std::string format_npy_header(const std::vector<std::uint64_t>& shape) {
    std::string dims;
    for (std::uint64_t d : shape) dims += std::to_string(d) + ", ";
    if (shape.size() > 1) dims.resize(dims.size() - 2);  // (3,) keeps its comma, (3, 4) does not
    std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + dims + "), }";
    // magic (6) + version (2) + length (2) + dict + padding + '\n' is a multiple of 64.
    std::size_t total = 10 + dict.size() + 1;
    dict.append((64 - total % 64) % 64, ' ');
    dict += '\n';
    std::string out(reinterpret_cast<const char*>(kMagic), sizeof kMagic);
    out += char(1);
    out += char(0);
    out += char(dict.size() & 0xff);
    out += char(dict.size() >> 8);
    return out + dict;
}

}  // namespace vkfuse::io

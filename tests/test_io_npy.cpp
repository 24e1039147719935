// Reading .npy files: every dtype, byte order, memory order, shape and header
// version vkfuse accepts, and every way a file can be broken.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "expect_error.hpp"
#include "npy_bytes.hpp"
#include "temp_dir.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

template <class T>
std::string encode(T value, bool big_endian) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (big_endian != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + sizeof(T));
    return std::string(bytes, sizeof(T));
}

struct DtypeCase {
    std::string descr;  // "<f4", ">u2", "|u1" ...
    bool fortran;
    std::vector<int> shape;  // (H, W) or (H, W, C)
    int major;
};

std::string shape_literal(const std::vector<int>& shape) {
    std::string s = "(";
    for (int d : shape) s += std::to_string(d) + ", ";
    s.resize(s.size() - 2);
    return s + ")";
}

// The stored sample at (y, x, c): an integer code for integer dtypes, a
// non-trivial fraction for floats, so every position is distinguishable.
double stored_value(const DtypeCase& t, int y, int x, int c) {
    int code = y * 37 + x * 11 + c * 5 + 3;
    if (t.descr[1] == 'u') return double(code % (t.descr[2] == '1' ? 256 : 65536));
    return code * 0.0137 - 0.25;  // floats are stored as is, negatives included
}

float expected_value(const DtypeCase& t, int y, int x, int c) {
    double v = stored_value(t, y, x, c);
    if (t.descr == "|u1" || t.descr.substr(1) == "u1") return float(v / 255.0);
    if (t.descr.substr(1) == "u2") return float(v / 65535.0);
    if (t.descr.substr(1) == "f4") return float(v);
    return float(double(v));
}

std::string element_bytes(const DtypeCase& t, double v) {
    bool big = t.descr[0] == '>';
    std::string code = t.descr.substr(1);
    if (code == "f4") return encode(float(v), big);
    if (code == "f8") return encode(double(v), big);
    if (code == "u1") return encode(std::uint8_t(v), big);
    return encode(std::uint16_t(v), big);
}

std::string file_for(const DtypeCase& t) {
    int h = t.shape[0], w = t.shape[1], c = t.shape.size() == 3 ? t.shape[2] : 1;
    std::string data;
    // Walk the elements in file order: last axis fastest (C) or first axis fastest (Fortran).
    for (int outer = 0; outer < h * w * c; ++outer) {
        int y, x, ch;
        if (t.fortran) {
            y = outer % h;
            x = (outer / h) % w;
            ch = outer / (h * w);
        } else {
            ch = outer % c;
            x = (outer / c) % w;
            y = outer / (c * w);
        }
        data += element_bytes(t, stored_value(t, y, x, ch));
    }
    return npy_bytes(dict_of(t.descr, t.fortran, shape_literal(t.shape)), data, t.major);
}

class NpyDtypes : public ::testing::TestWithParam<DtypeCase> {};

TEST_P(NpyDtypes, ReadsEverySampleAtItsPlace) {
    const DtypeCase& t = GetParam();
    TempDir dir;
    std::string path = dir.file("in.npy");
    write_bytes(path, file_for(t));
    Image img = io::read_image(path);
    int stored_c = t.shape.size() == 3 ? t.shape[2] : 1;
    ASSERT_EQ(img.height, t.shape[0]);
    ASSERT_EQ(img.width, t.shape[1]);
    ASSERT_EQ(img.channels, stored_c == 1 ? 1 : 3);  // C = 4 drops alpha
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < img.channels; ++c)
                ASSERT_EQ(img.at(y, x, c), expected_value(t, y, x, c)) << "at " << y << "," << x << "," << c;
}

std::vector<DtypeCase> all_dtype_cases() {
    std::vector<DtypeCase> cases;
    for (std::string descr : {"<f4", ">f4", "<f8", ">f8", "|u1", "<u1", "<u2", ">u2"})
        for (bool fortran : {false, true})
            for (std::vector<int> shape : {std::vector<int>{5, 7}, {4, 3, 1}, {3, 5, 3}, {2, 6, 4}, {1, 1}})
                cases.push_back({descr, fortran, shape, 1});
    for (int major : {2, 3}) cases.push_back({"<f4", false, {3, 4, 3}, major});
    return cases;
}

std::string case_name(const ::testing::TestParamInfo<DtypeCase>& info) {
    const DtypeCase& t = info.param;
    std::string name = std::string(t.descr[0] == '>' ? "be_" : "le_") + t.descr.substr(1) + (t.fortran ? "_F_" : "_C_");
    for (int d : t.shape) name += std::to_string(d) + "x";
    return name + "v" + std::to_string(t.major) + "_" + std::to_string(info.index);
}

INSTANTIATE_TEST_SUITE_P(AllDtypes, NpyDtypes, ::testing::ValuesIn(all_dtype_cases()), case_name);

TEST(NpyRead, AcceptsDoubleQuotesOddSpacingAndPython2Longs) {
    TempDir dir;
    std::string path = dir.file("odd.NPY");  // extension is case-insensitive
    std::string data = encode(0.25f, false) + encode(0.5f, false);
    write_bytes(path, npy_bytes("{ \"shape\" : (1L,2L) ,\"fortran_order\":False, \"descr\":\"<f4\"}", data));
    Image img = io::read_image(path);
    EXPECT_EQ(img.width, 2);
    EXPECT_EQ(img.at(0, 1, 0), 0.5f);
}

struct BadFile {
    std::string name;
    std::string bytes;
    ErrorKind kind;
    std::string fragment;
};

std::vector<BadFile> bad_files() {
    std::string f4x4 = std::string(16, '\0');
    return {
        {"empty", "", ErrorKind::Format, "empty file"},
        {"magic", "PK\x03\x04 definitely not numpy", ErrorKind::Format, "not a .npy file"},
        {"version", npy_bytes(dict_of("<f4", false, "(2, 2)"), f4x4, 4), ErrorKind::Format, "unsupported .npy version 4.0"},
        {"short_prefix", std::string("\x93NUMPY\x02\x00\x10", 9), ErrorKind::Format, "not a .npy file"},
        {"header_len", std::string("\x93NUMPY\x01\x00\xff\x7f{'descr'", 17), ErrorKind::Format, "truncated .npy header"},
        {"truncated", npy_bytes(dict_of("<f4", false, "(64, 64, 3)"), std::string(1000, '\0')), ErrorKind::Format,
         "truncated: header says 64x64x3 float32 (49152 bytes) but the file has 1000"},
        {"trailing", npy_bytes(dict_of("<f4", false, "(2, 2)"), f4x4 + "xx"), ErrorKind::Format, "corrupt: header says 2x2"},
        {"dtype_i4", npy_bytes(dict_of("<i4", false, "(2, 2)"), f4x4), ErrorKind::Format, "unsupported dtype '<i4'"},
        {"dtype_pipe_f4", npy_bytes(dict_of("|f4", false, "(2, 2)"), f4x4), ErrorKind::Format, "unsupported dtype"},
        {"structured", npy_bytes("{'descr': [('a', '<f4')], 'fortran_order': False, 'shape': (2,), }", f4x4),
         ErrorKind::Format, "expected a quoted string"},
        {"rank1", npy_bytes(dict_of("<f4", false, "(4,)"), f4x4), ErrorKind::Format, "unsupported shape 4"},
        {"rank0", npy_bytes(dict_of("<f4", false, "()"), f4x4), ErrorKind::Format, "unsupported shape ()"},
        {"rank4", npy_bytes(dict_of("<f4", false, "(1, 2, 2, 1)"), f4x4), ErrorKind::Format, "unsupported shape"},
        {"two_channels", npy_bytes(dict_of("<f4", false, "(1, 2, 2)"), f4x4), ErrorKind::Format, "unsupported shape 1x2x2"},
        {"zero_dim", npy_bytes(dict_of("<f4", false, "(0, 4)"), ""), ErrorKind::Format, "empty image"},
        {"huge", npy_bytes(dict_of("<f4", false, "(100000, 100000, 3)"), f4x4), ErrorKind::Format, "image too large"},
        {"overflow", npy_bytes(dict_of("<f4", false, "(99999999999999999999999, 1)"), f4x4), ErrorKind::Format,
         "dimension out of range"},
        {"negative", npy_bytes(dict_of("<f4", false, "(-2, 2)"), f4x4), ErrorKind::Format, "non-negative integer"},
        {"missing_key", npy_bytes("{'descr': '<f4', 'shape': (2, 2), }", f4x4), ErrorKind::Format, "missing"},
        {"extra_key", npy_bytes("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2), 'x': 1}", f4x4),
         ErrorKind::Format, "unexpected or repeated key 'x'"},
        {"repeated_key", npy_bytes("{'descr': '<f4', 'descr': '<f4', 'shape': (2, 2)}", f4x4), ErrorKind::Format,
         "unexpected or repeated key 'descr'"},
        {"bad_bool", npy_bytes("{'descr': '<f4', 'fortran_order': 0, 'shape': (2, 2)}", f4x4), ErrorKind::Format,
         "expected True or False"},
        {"unterminated", npy_bytes("{'descr': '<f4", ""), ErrorKind::Format, "unterminated string"},
        {"garbage", npy_bytes("hello", f4x4), ErrorKind::Format, "expected '{'"},
        {"unclosed", npy_bytes("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2", f4x4), ErrorKind::Format,
         "expected ')'"},
        {"nan", npy_bytes(dict_of("<f4", false, "(2, 3)"),
                          encode(0.f, false) + encode(0.f, false) + encode(0.f, false) + encode(0.f, false) +
                              encode(std::numeric_limits<float>::quiet_NaN(), false) + encode(0.f, false)),
         ErrorKind::Numeric, "NaN at row 1, column 1, channel 0"},
        {"inf", npy_bytes(dict_of("<f4", false, "(1, 1, 3)"),
                          encode(0.f, false) + encode(0.f, false) + encode(-INFINITY, false)),
         ErrorKind::Numeric, "-Inf at row 0, column 0, channel 2"},
        {"f8_beyond_float", npy_bytes(dict_of("<f8", false, "(1, 1)"), encode(1e300, false)), ErrorKind::Numeric,
         "Inf at row 0, column 0, channel 0"},
    };
}

TEST(NpyRead, EveryBrokenFileGivesItsErrorNamingThePath) {
    TempDir dir;
    for (const BadFile& bad : bad_files()) {
        SCOPED_TRACE(bad.name);
        std::string path = dir.file(bad.name + ".npy");
        write_bytes(path, bad.bytes);
        expect_read_error(path, bad.kind, bad.fragment);
    }
}

TEST(NpyRead, MissingFileAndDirectoryAreIoErrors) {
    TempDir dir;
    expect_read_error(dir.file("absent.npy"), ErrorKind::Io, "cannot open: No such file or directory");
    std::filesystem::create_directory(dir.file("folder.npy"));
    expect_read_error(dir.file("folder.npy"), ErrorKind::Io, "not a regular file");
}

TEST(NpyRead, UnknownExtensionIsAnInvalidArgument) {
    TempDir dir;
    write_bytes(dir.file("a.tiff"), "x");
    expect_read_error(dir.file("a.tiff"), ErrorKind::InvalidArgument, "unknown image format '.tiff'");
    expect_read_error(dir.file("noext"), ErrorKind::InvalidArgument, "(no extension)");
}

// Every prefix of a valid file is rejected cleanly, never read out of bounds.
TEST(NpyRead, EveryTruncationIsAFormatError) {
    std::string good = file_for({"<f8", true, {3, 2, 3}, 2});
    TempDir dir;
    std::string path = dir.file("cut.npy");
    for (std::size_t n = 0; n < good.size(); ++n) {
        write_bytes(path, good.substr(0, n));
        SCOPED_TRACE(n);
        expect_read_error(path, ErrorKind::Format, "");
    }
}

// Random damage to the header either still parses or gives an Error; it never crashes.
TEST(NpyRead, RandomHeaderDamageNeverCrashes) {
    std::string good = file_for({"<u2", false, {4, 4, 3}, 1});
    TempDir dir;
    std::string path = dir.file("fuzz.npy");
    std::mt19937 rng(7);
    for (int trial = 0; trial < 2000; ++trial) {
        std::string bad = good;
        for (int k = 0; k < 3; ++k) bad[rng() % 128] = char(rng());
        write_bytes(path, bad);
        try {
            Image img = io::read_image(path);
            EXPECT_EQ(img.size(), img.pixels() * std::size_t(img.channels));
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
        }
    }
}

}  // namespace
}  // namespace vkfuse::test

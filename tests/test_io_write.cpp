// Writing images: exact .npy round trips, PNG quantization, and the promise
// that a failed write leaves nothing behind.
#include <gtest/gtest.h>

#include <cmath>

#include "expect_error.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

Image values_beyond_unit_range(int h, int w, int c) {
    Image img = convert<float>(random_image(h, w, c, 5));
    for (std::size_t i = 0; i < img.size(); i += 7) img.data[i] = img.data[i] * 3.0f - 1.0f;  // fused may leave [0, 1]
    return img;
}

TEST(NpyWrite, RoundTripsFloat32Exactly) {
    TempDir dir;
    for (int c : {1, 3}) {
        Image img = values_beyond_unit_range(17, 10, c);
        std::string path = dir.file("out" + std::to_string(c) + ".npy");
        io::write_image(path, img);
        Image back = io::read_image(path);
        ASSERT_TRUE(back.same_shape(img));
        EXPECT_EQ(back.data, img.data);
    }
}

TEST(NpyWrite, HeaderIsNumpysFloat32LayoutPaddedTo64) {
    TempDir dir;
    io::write_image(dir.file("g.npy"), Image(4, 6, 1));
    io::write_image(dir.file("c.npy"), Image(4, 6, 3));
    std::string gray = read_bytes(dir.file("g.npy")), color = read_bytes(dir.file("c.npy"));
    EXPECT_EQ(gray.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
    std::size_t header = 10 + std::size_t(std::uint8_t(gray[8])) + 256 * std::uint8_t(gray[9]);
    EXPECT_EQ(header % 64, 0u);
    EXPECT_EQ(gray.size(), header + 4 * 6 * 4);
    EXPECT_EQ(gray[header - 1], '\n');
    EXPECT_NE(gray.find("'descr': '<f4'"), std::string::npos);
    EXPECT_NE(gray.find("'fortran_order': False"), std::string::npos);
    EXPECT_NE(gray.find("'shape': (4, 6)"), std::string::npos);  // C = 1 is stored as (H, W)
    EXPECT_NE(color.find("'shape': (4, 6, 3)"), std::string::npos);
}

TEST(PngWrite, ClampsAndRoundsTo8Bits) {
    TempDir dir;
    Image img(1, 6, 1);
    img.data = {-0.5f, 0.0f, 0.2f, 0.5f, 1.0f, 1.7f};
    io::write_image(dir.file("q.png"), img);
    Image back = io::read_image(dir.file("q.png"));
    ASSERT_TRUE(back.same_shape(img));
    const int expected[] = {0, 0, 51, 128, 255, 255};  // round(clamp(v) * 255), halves away from zero
    for (int x = 0; x < 6; ++x) EXPECT_EQ(back.at(0, x, 0), float(expected[x] / 255.0)) << x;
}

TEST(PngWrite, RoundTripsRgbAndGrayWithinHalfAStep) {
    TempDir dir;
    for (int c : {1, 3}) {
        Image img = convert<float>(structured_image(23, 31, c, 3));
        std::string path = dir.file("rt.png");
        io::write_image(path, img);
        Image back = io::read_image(path);
        ASSERT_TRUE(back.same_shape(img));
        EXPECT_LE(max_abs_diff(back, convert<double>(img)), 0.5 / 255 + 1e-7);
    }
}

TEST(ImageWrite, RejectsWhatTheFormatCannotHold) {
    TempDir dir;
    Image nan(2, 2, 3);
    nan.at(1, 0, 2) = NAN;
    std::string png = dir.file("nan.png");
    expect_error([&] { io::write_image(png, nan); }, png, ErrorKind::Numeric, "NaN at row 1, column 0, channel 2");
    std::string two = dir.file("two.png");
    expect_error([&] { io::write_image(two, Image(2, 2, 2)); }, two, ErrorKind::InvalidArgument, "1 or 3 channels");
    Image broken(2, 2, 3);
    broken.data.pop_back();
    std::string npy = dir.file("broken.npy");
    expect_error([&] { io::write_image(npy, broken); }, npy, ErrorKind::InvalidArgument, "holding 11 values");
    std::string jpg = dir.file("x.jpg");
    expect_error([&] { io::write_image(jpg, Image(2, 2, 3)); }, jpg, ErrorKind::InvalidArgument, "unknown image format");
    EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageWrite, NpyKeepsNonFiniteValuesAsComputed) {
    TempDir dir;
    Image img(1, 2, 1);
    img.data = {NAN, 0.5f};
    io::write_image(dir.file("nan.npy"), img);  // reading it back is what rejects NaN
    EXPECT_THROW(io::read_image(dir.file("nan.npy")), Error);
}

TEST(ImageWrite, UnwritableDirectoryIsAnIoErrorAndCreatesNothing) {
    TempDir dir;
    std::string path = dir.file("missing/out.npy");
    expect_error([&] { io::write_image(path, Image(2, 2, 1)); }, path, ErrorKind::Io, "No such file or directory");
    write_bytes(dir.file("plain"), "x");
    std::string under_file = dir.file("plain/out.png");
    expect_error([&] { io::write_image(under_file, Image(2, 2, 1)); }, under_file, ErrorKind::Io, "Not a directory");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"plain"});
}

// The rename is the last step; when it fails the temporary must go too.
TEST(ImageWrite, FailedRenameLeavesNoTemporary) {
    TempDir dir;
    std::filesystem::create_directories(dir.file("out.npy/occupied"));
    std::string path = dir.file("out.npy");
    expect_error([&] { io::write_image(path, Image(3, 3, 3)); }, path, ErrorKind::Io, "cannot replace");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.npy"});
}

TEST(ImageWrite, ReplacesAnExistingFileWhole) {
    TempDir dir;
    std::string path = dir.file("same.npy");
    write_bytes(path, std::string(100000, 'z'));
    Image img = values_beyond_unit_range(3, 4, 3);
    io::write_image(path, img);
    EXPECT_EQ(io::read_image(path).data, img.data);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"same.npy"});
    EXPECT_EQ(std::filesystem::status(path).permissions() & std::filesystem::perms::others_read,
              std::filesystem::perms::others_read);
}

TEST(CheckFinite, NamesWhatAndWhereAndWhich) {
    Image img(3, 4, 3);
    io::check_finite(img, "x");
    img.at(2, 1, 1) = -INFINITY;
    expect_error([&] { io::check_finite(img, "frame 2"); }, "frame 2", ErrorKind::Numeric,
                 "-Inf at row 2, column 1, channel 1");
    img.at(0, 3, 0) = NAN;
    expect_error([&] { io::check_finite(img, "frame 2"); }, "frame 2", ErrorKind::Numeric,
                 "NaN at row 0, column 3, channel 0");
}

}  // namespace
}  // namespace vkfuse::test

// Misuse of the CPU reference API: malformed images, backgrounds of another
// shape and non-finite values are Errors naming what is wrong, never aborts.
#include <gtest/gtest.h>

#include <limits>

#include "expect_error.hpp"
#include "test_support.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

TEST(CpuApiErrors, MetricsOfMalformedImages) {
    expect_error([] { metrics_reference(ImageD()); }, "image", ErrorKind::InvalidArgument,
                 "shape 0x0x0 is not H x W x {1, 3}");
    expect_error([] { metrics_reference(ImageD(4, 4, 2)); }, "image", ErrorKind::InvalidArgument, "4x4x2");
    ImageD short_data(4, 4, 3);
    short_data.data.pop_back();
    expect_error([&] { metrics_reference(short_data); }, "image", ErrorKind::InvalidArgument, "4x4x3");
    ImageD inf = random_image(4, 4, 3, 1);
    inf.at(1, 2, 1) = -std::numeric_limits<double>::infinity();
    expect_error([&] { metrics_reference(inf); }, "image", ErrorKind::Numeric, "-Inf at row 1, column 2, channel 1");
}

TEST(CpuApiErrors, MetricsWithABadBackground) {
    const ImageD img = random_image(4, 4, 3, 1);
    const ImageD other = random_image(4, 5, 3, 2);
    expect_error([&] { metrics_reference(img, &other); }, "background", ErrorKind::Shape,
                 "shape 4x5x3 differs from the image's 4x4x3");
    ImageD nan = img;
    nan.at(3, 3, 2) = std::numeric_limits<double>::quiet_NaN();
    expect_error([&] { metrics_reference(img, &nan); }, "background", ErrorKind::Numeric, "NaN at row 3, column 3");
}

TEST(CpuApiErrors, FusionOfMalformedFrames) {
    FusionSpec spec;
    spec.method = Method::Brovey;
    std::vector<ImageD> frames{random_image(4, 4, 3, 1), random_image(4, 4, 3, 2)};
    frames[1].data.resize(5);
    expect_error([&] { fuse_reference(frames, spec); }, "frame 2", ErrorKind::Shape, "differs from frame 1's 4x4x3");
    expect_error([&] { fuse_reference(std::vector<ImageD>{ImageD()}, spec); }, "image size 0x0",
                 ErrorKind::InvalidArgument, "both sides must be >= 1");
}

}  // namespace
}  // namespace vkfuse::test

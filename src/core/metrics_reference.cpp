// metrics_reference(): the paper's sharpness, RMS contrast and background
// difference exactly as docs/spec.md defines them, in double precision with
// compensated sums.
#include <cmath>
#include <string>

#include "core/check_finite.hpp"
#include "core/compensated_sum.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse {
namespace {

// Y = 0.299 R + 0.587 G + 0.114 B (C = 3), Y = I (C = 1). Computed on demand
// rather than stored: at 8192 x 8192 a luma plane would add 512 MB to the
// 1.6 GB image.
struct Luma {
    const ImageD& img;
    double operator()(int y, int x) const {
        if (img.channels == 1) return img.at(y, x, 0);
        return 0.299 * img.at(y, x, 0) + 0.587 * img.at(y, x, 1) + 0.114 * img.at(y, x, 2);
    }
};

// numpy.gradient along one axis of length n at index i, given f(i):
// central difference inside, one-sided at the ends, 0 when n == 1.
template <class F>
double gradient(F f, int i, int n) {
    if (n == 1) return 0;
    if (i == 0) return f(1) - f(0);
    if (i == n - 1) return f(n - 1) - f(n - 2);
    return (f(i + 1) - f(i - 1)) / 2;
}

double sharpness(const ImageD& img) {
    const Luma luma{img};
    core::CompensatedSum sum;
    for (int r = 0; r < img.height; ++r)
        for (int c = 0; c < img.width; ++c) {
            const double gy = gradient([&](int i) { return luma(i, c); }, r, img.height);
            const double gx = gradient([&](int i) { return luma(r, i); }, c, img.width);
            sum.add(std::sqrt(gx * gx + gy * gy));
        }
    return sum.value() / double(img.pixels());
}

// Population standard deviation, two-pass (mean first) so it does not cancel.
double contrast(const ImageD& img) {
    const Luma luma{img};
    core::CompensatedSum sum;
    for (int r = 0; r < img.height; ++r)
        for (int c = 0; c < img.width; ++c) sum.add(luma(r, c));
    const double mean = sum.value() / double(img.pixels());
    core::CompensatedSum squares;
    for (int r = 0; r < img.height; ++r)
        for (int c = 0; c < img.width; ++c) {
            const double d = luma(r, c) - mean;
            squares.add(d * d);
        }
    return std::sqrt(squares.value() / double(img.pixels()));
}

std::string shape_text(const ImageD& f) {
    return std::to_string(f.height) + "x" + std::to_string(f.width) + "x" + std::to_string(f.channels);
}

double background_diff(const ImageD& img, const ImageD& bg) {
    if (!img.same_shape(bg))
        throw Error(ErrorKind::Shape,
                    "background: shape " + shape_text(bg) + " differs from the image's " + shape_text(img));
    core::require_finite(bg, "background");
    core::CompensatedSum sum;
    for (std::size_t i = 0; i < img.data.size(); ++i) sum.add(std::abs(img.data[i] - bg.data[i]));
    return sum.value() / double(img.data.size());
}

}  // namespace

Metrics metrics_reference(const ImageD& img, const ImageD* background, MetricSet which) {
    if (img.height < 1 || img.width < 1 || (img.channels != 1 && img.channels != 3) ||
        img.data.size() != img.pixels() * img.channels)
        throw Error(ErrorKind::InvalidArgument, "image: shape " + shape_text(img) + " is not H x W x {1, 3}");
    core::require_finite(img, "image");
    Metrics m;
    m.sharpness = which.has(Metric::Sharpness) ? sharpness(img) : std::nan("");
    m.contrast = which.has(Metric::Contrast) ? contrast(img) : std::nan("");
    if (background != nullptr && which.has(Metric::BackgroundDiff)) m.background_diff = background_diff(img, *background);
    return m;
}

}  // namespace vkfuse

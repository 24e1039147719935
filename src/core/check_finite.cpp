#include "core/check_finite.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "vkfuse/core/error.hpp"

namespace vkfuse::core {

namespace {

std::string position(int y, int x, int c) {
    return "row " + std::to_string(y) + ", column " + std::to_string(x) + ", channel " + std::to_string(c);
}

// Calls bad(v, y, x, c) for the first sample where is_bad(v), in row order.
template <class IsBad, class Bad>
void first_bad_sample(const ImageD& image, IsBad is_bad, Bad bad) {
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < image.channels; ++c)
                if (is_bad(image.at(y, x, c))) bad(image.at(y, x, c), y, x, c);
}

}  // namespace

void require_finite(const ImageD& image, const std::string& what) {
    first_bad_sample(
        image, [](double v) { return !std::isfinite(v); },
        [&](double v, int y, int x, int c) {
            throw Error(ErrorKind::Numeric,
                        what + ": " + (std::isnan(v) ? "NaN" : v > 0 ? "Inf" : "-Inf") + " at " + position(y, x, c));
        });
}

void require_float32_range(const ImageD& image, const std::string& what) {
    first_bad_sample(
        image, [](double v) { return std::abs(v) > double(std::numeric_limits<float>::max()); },
        [&](double v, int y, int x, int c) {
            char value[32];
            std::snprintf(value, sizeof value, "%.9g", v);
            throw Error(ErrorKind::Numeric,
                        what + " value " + value + " at " + position(y, x, c) + " lies beyond float32's range");
        });
}

}  // namespace vkfuse::core

#include "core/check_finite.hpp"

#include <cmath>

#include "vkfuse/error.hpp"

namespace vkfuse::core {

void require_finite(const ImageD& image, const std::string& what) {
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < image.channels; ++c) {
                const double v = image.at(y, x, c);
                if (std::isfinite(v)) continue;
                throw Error(ErrorKind::Numeric, what + ": " + (std::isnan(v) ? "NaN" : v > 0 ? "Inf" : "-Inf") + " at row " +
                                                    std::to_string(y) + ", column " + std::to_string(x) +
                                                    ", channel " + std::to_string(c));
            }
}

}  // namespace vkfuse::core

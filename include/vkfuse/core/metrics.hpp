// vkfuse/core/metrics.hpp - the paper's image quality metrics (docs/spec.md, "Metrics").
#pragma once
#include <optional>

namespace vkfuse {

struct Metrics {
    double sharpness = 0;   // mean gradient magnitude of luma (numpy.gradient)
    double contrast = 0;    // RMS contrast: population std of luma
    std::optional<double> background_diff;  // mean |I - B| over pixels and channels
};

}  // namespace vkfuse

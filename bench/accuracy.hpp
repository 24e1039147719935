// Error of a result against the reference: the fused image sample by sample,
// each metric relative to its reference value.
#pragma once
#include <cstddef>

#include "vkfuse/image.hpp"
#include "vkfuse/metrics.hpp"

namespace vkfuse::bench {

inline constexpr double kFusedTolerance = 1e-5;  // docs/spec.md: Vulkan fp32 vs reference

// Accumulates over several sensors' images.
struct FusedError {
    double max_abs = 0;
    double sum_abs = 0;
    std::size_t samples = 0;
    std::size_t over_tolerance = 0;  // samples with |error| > kFusedTolerance

    // Throws std::runtime_error when the shapes differ.
    void add(const Image& got, const ImageD& want);
    void add(const ImageD& got, const ImageD& want);  // the CPU reference's own output
    double mean_abs() const { return samples ? sum_abs / double(samples) : 0.0; }
};

// Worst relative error of each metric over the sensors added.
struct MetricError {
    double sharpness = 0;
    double contrast = 0;
    double background_diff = 0;

    void add(const Metrics& got, const Metrics& want);
    double worst() const;
};

}  // namespace vkfuse::bench

// Error of a result against the reference: the fused image sample by sample,
#pragma once
#include <cstddef>
#include <vector>

#include "inputs.hpp"
#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/core/metrics.hpp"

namespace vkfuse::bench {

// What the double-precision CPU reference says a sensor's cycle must give:
// the truth every backend's and peer's error is measured against.

struct Expected {
    int sensor = 0;
    ImageD fused;
    Metrics metrics;  // with background_diff
};

// The sensors whose results are compared: the first, the last and up to two
// evenly between (checking every one of 64 sensors would cost more reference
// time than the benchmark itself; these catch a wrong sensor offset).
std::vector<int> checked_sensors(int sensors);

// Reference results for checked_sensors(in.sensors()), each scene computed once.
std::vector<Expected> expected_results(const Inputs& in, const FusionSpec& spec);

// Error of a result against the reference: the fused image sample by sample,
// each metric relative to its reference value.

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

// What the double-precision CPU reference says a sensor's cycle must give:
// the truth every backend's and peer's error is measured against.
#pragma once
#include <vector>

#include "inputs.hpp"
#include "vkfuse/fusion.hpp"
#include "vkfuse/metrics.hpp"

namespace vkfuse::bench {

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

}  // namespace vkfuse::bench

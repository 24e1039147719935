// Measuring one cell on one backend: the timed cycle is what a sensor loop
// does every cycle (fuse the K frames of every sensor, compute the three
// metrics, bring the fused images to the host), then the error of the last
// cycle's results against the reference.
#pragma once
#include <vector>

#include "accuracy.hpp"
#include "inputs.hpp"
#include "result.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::bench {

inline constexpr const char* kCpuDevice = "CPU reference (double, 1 thread)";

// The double-precision CPU reference (vkfuse::fuse_reference and
// metrics_reference, as `vkfuse --backend cpu` runs them), sensor after sensor.
CellResult measure_cpu(const Cell& cell, const Inputs& in, const std::vector<Expected>& expected,
                       const RunPolicy& policy);

// One vkfuse::Plan for all S sensors. With profile, Plan::profile()'s stage
// times are collected from every timed run. Throws vkfuse::Error on device failure.
CellResult measure_vulkan(Context& context, const Cell& cell, const Inputs& in, const std::vector<Expected>& expected,
                          const RunPolicy& policy, bool profile);

// The fixed cost of a cycle on this device, what every cell pays whatever its
// work: a plan whose one small dispatch fuses a 4x4 image (brovey, K = 2, no
// metrics), run and read back as measure_vulkan runs a cell.
Timing time_empty_cycle(Context& context, const RunPolicy& policy);

}  // namespace vkfuse::bench

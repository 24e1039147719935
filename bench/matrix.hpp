// Which cells a run measures: the scope's slices of the matrix, narrowed or
// replaced axis by axis by the filters, each cell checked for fit.
#pragma once
#include <vector>

#include "cell.hpp"
#include "options.hpp"

namespace vkfuse::bench {

// The cells to run, cells of one workload adjacent (cpu before vulkan), small
// workloads first. Cells that cannot fit memory_budget bytes carry a skip
// reason; invalid combinations (channel-sum needs K = 3) are left out.
// Throws UsageError when the filters leave no cell at all.
std::vector<Cell> build_matrix(const Options& options, double memory_budget);

}  // namespace vkfuse::bench

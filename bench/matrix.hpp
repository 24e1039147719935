// Which cells a run measures: the scope's slices of the matrix, narrowed or
#pragma once
#include <vector>

#include "options.hpp"
#include "result.hpp"

namespace vkfuse::bench {

// Which cells a run measures: the scope's slices of the matrix, narrowed or
// replaced axis by axis by the filters, each cell checked for fit.

// The cells to run, cells of one workload adjacent (cpu before vulkan), small
// workloads first. Cells that cannot fit memory_budget bytes carry a skip
// reason; invalid combinations (channel-sum needs K = 3) are left out.
// Throws UsageError when the filters leave no cell at all.
std::vector<Cell> build_matrix(const Options& options, double memory_budget);

// How much memory a cell needs, so cells that cannot fit are skipped with a
// reason instead of failing half way (or swapping the machine to a halt).

// Host plus device bytes one cell needs at its peak, estimated from the plan's
// buffers (upload, planar input, the method's intermediates, readback) and the
// host's frames and reference images. On lavapipe device memory is host memory.
double estimated_bytes(const Cell& cell);

// limit_gib when > 0, else 80% of MemAvailable from /proc/meminfo (or 4 GiB
// when that cannot be read).
double memory_budget(double limit_gib);

}  // namespace vkfuse::bench

// How much memory a cell needs, so cells that cannot fit are skipped with a
// reason instead of failing half way (or swapping the machine to a halt).
#pragma once
#include "cell.hpp"

namespace vkfuse::bench {

// Host plus device bytes one cell needs at its peak, estimated from the plan's
// buffers (upload, planar input, the method's intermediates, readback) and the
// host's frames and reference images. On lavapipe device memory is host memory.
double estimated_bytes(const Cell& cell);

// limit_gib when > 0, else 80% of MemAvailable from /proc/meminfo (or 4 GiB
// when that cannot be read).
double memory_budget(double limit_gib);

}  // namespace vkfuse::bench

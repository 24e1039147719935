// One benchmark run: find the device and the peers, measure every cell of the
// matrix workload by workload, report.
#pragma once
#include "options.hpp"

namespace vkfuse::bench {

// Returns the process exit status. Throws UsageError before measuring anything
// when the options cannot be honoured (no cell matches, an output directory is missing).
int run_bench(const Options& options);

}  // namespace vkfuse::bench

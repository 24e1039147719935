// vkfuse-bench --windows: a sliding window's fused rate and latency against
// the error it costs, cycle beside sliding, on simulated scenes.
#pragma once
#include "options.hpp"

namespace vkfuse::bench {

// Runs every scene (still, tap and slide at 0.5, 1 and 2 s) under both
// windows with 2 and 3 settings (--frames picks), prints a row each, and
// writes them to --json and --plot. Returns the exit status.
int run_windows(const Options& options);

}  // namespace vkfuse::bench

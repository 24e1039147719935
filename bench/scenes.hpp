// vkfuse-bench --scenes: skipping's time against its error on simulated scenes.
#pragma once
#include "options.hpp"

namespace vkfuse::bench {

// Runs every scene under skip off and idle at three thresholds, prints a row
// each (and writes them to --json). Returns the exit status.
int run_scenes(const Options& options);

}  // namespace vkfuse::bench

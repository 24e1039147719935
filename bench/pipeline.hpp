// vkfuse-bench --pipeline: a sensor loop whose cycle is one round trip against
// the same loop with two cycles in flight (PlanConfig::cycles_in_flight).
#pragma once
#include "options.hpp"

namespace vkfuse::bench {

// Runs each method's loop both ways on the same frames, prints a row each
// (and writes them to --json). Returns the exit status: 1 where the two ways
// gave different results.
int run_pipeline(const Options& options);

}  // namespace vkfuse::bench

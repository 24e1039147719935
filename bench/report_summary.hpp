// The lines after the table: accuracy of the Vulkan cells against docs/spec.md's
// tolerance, and what batching sensors buys.
#pragma once
#include <cstdio>
#include <vector>

#include "result.hpp"

namespace vkfuse::bench {

void print_summary(std::FILE* out, const std::vector<CellResult>& results);

}  // namespace vkfuse::bench

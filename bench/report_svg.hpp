// --plot FILE.svg: time against error, log-log, one colour per method and one
// marker per backend and precision, so the speed/accuracy trade-off is seen.
#pragma once
#include <string>
#include <vector>

#include "result.hpp"

namespace vkfuse::bench {

// Writes a self-contained SVG (no scripts, no fonts beyond sans-serif)
// atomically; throws vkfuse::Error(Io).
void write_plot(const std::string& path, const std::vector<CellResult>& results, const std::string& device);

}  // namespace vkfuse::bench

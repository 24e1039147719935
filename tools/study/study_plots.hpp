// study_plots.hpp - the study's pictures as SVG: what report.md shows.
#pragma once
#include <string>

#include "vkfuse/study/study.hpp"

namespace vkfuse::cli {

// One bar per method: the share of its fusions that improve every metric.
std::string methods_svg(const StudyResult& result);
// Per metric, the greedy sequence's mean gain against its length n.
std::string greedy_svg(const StudyResult& result);
// A row per setting fused with the static one, a column per metric, each
// cell coloured by its gain (blue below 1, white at 1, red above).
std::string pairing_svg(const StudyResult& result);

}  // namespace vkfuse::cli

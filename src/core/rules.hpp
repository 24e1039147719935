// core/rules.hpp - the fusion rules (docs/spec.md, "Rules"): how K coefficients at
// one position, one per frame, become one.
#pragma once
#include <span>
#include <vector>

#include "core/plane.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse::core {

// max-abs: the value of largest |v| (ties: the lowest frame index, so the
//          first frame wins; NaN never occurs, inputs are checked finite);
// mean:    sum / K, summed in frame order;
// max, min: the largest / smallest value.
double combine(Rule rule, std::span<const double> values);

// combine() at every position of K planes of one shape.
Plane combine_planes(Rule rule, std::span<const Plane* const> planes);

}  // namespace vkfuse::core

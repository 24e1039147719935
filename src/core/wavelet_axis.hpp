// core/wavelet_axis.hpp - one DWT level along one axis of a plane, per mode:
// the building block wavedec2/waverec2 compose (internal to src/core).
#pragma once
#include "core/line_gather.hpp"
#include "core/plane.hpp"
#include "core/wavelet.hpp"

namespace vkfuse::core {

// Approximation (lo) and detail (hi) along one axis.
struct Bands {
    Plane lo, hi;
};

// pywt's periodization analysis (one filter of `length` taps over a line of
// n samples: ceil(n/2) outputs) and synthesis (one band of n coefficients to
// 2n samples) as gather tables, with core/wavelet.hpp's index formulas. The
// index tables depend on the filter's length only, not on its taps.
LineGather periodization_analysis(const std::array<double, 10>& filter, int length, int n);
LineGather periodization_synthesis(const std::array<double, 10>& filter, int length, int n);

// Periodization: lo and hi both ceil(n/2) long along the axis; merge needs equal
// lengths N and returns 2N.
Bands split_axis_periodization(const Plane& p, int axis, const FilterBank& fb);
Plane merge_axis_periodization(const Plane& lo, const Plane& hi, int axis, const FilterBank& fb);

// Lifting: lo ceil(n/2), hi floor(n/2); merge returns lo + hi long.
Bands split_axis_lifting(const Plane& p, int axis, const LiftingScheme& ls);
Plane merge_axis_lifting(const Plane& lo, const Plane& hi, int axis, const LiftingScheme& ls);

}  // namespace vkfuse::core

// core/wavelet_axis.hpp - one DWT level along one axis of a plane, per mode:
// the building block wavedec2/waverec2 compose (internal to src/core).
#pragma once
#include "core/plane.hpp"
#include "core/wavelet.hpp"

namespace vkfuse::core {

// Approximation (lo) and detail (hi) along one axis.
struct Bands {
    Plane lo, hi;
};

// Periodization: lo and hi both ceil(n/2) long along the axis; merge needs equal
// lengths N and returns 2N.
Bands split_axis_periodization(const Plane& p, int axis, const FilterBank& fb);
Plane merge_axis_periodization(const Plane& lo, const Plane& hi, int axis, const FilterBank& fb);

// Lifting: lo ceil(n/2), hi floor(n/2); merge returns lo + hi long.
Bands split_axis_lifting(const Plane& p, int axis, const LiftingScheme& ls);
Plane merge_axis_lifting(const Plane& lo, const Plane& hi, int axis, const LiftingScheme& ls);

}  // namespace vkfuse::core

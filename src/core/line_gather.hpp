// core/line_gather.hpp - a linear map from one line to another written as a
// gather table: output i = sum_t weight[i][t] * input[index[i][t]]. The
// periodization DWT/IDWT are built as such tables once per line length (all
// index arithmetic happens there) and then applied to every row or column.
#pragma once
#include <span>
#include <vector>

#include "core/plane.hpp"

namespace vkfuse::core {

struct LineGather {
    int outputs = 0;
    int taps = 0;
    std::vector<int> index;      // outputs x taps, row-major
    std::vector<double> weight;  // outputs x taps
};

// out[i] (+)= sum_t weight[i][t] * in[index[i][t]]; out.size() == g.outputs.
void gather_line(const LineGather& g, std::span<const double> in, std::span<double> out, bool accumulate);

// The same map applied along one axis of a plane (axis 0: down every column,
// axis 1: along every row). The result's length along that axis is g.outputs.
Plane gather_axis(const Plane& in, int axis, const LineGather& g);
// As gather_axis, added into out (which already has the result's shape).
void gather_axis_add(const Plane& in, int axis, const LineGather& g, Plane& out);

}  // namespace vkfuse::core

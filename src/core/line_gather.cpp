// Applying gather tables along rows or columns. Along axis 0 whole rows are
// combined, so the inner loop runs over contiguous memory.
#include "core/line_gather.hpp"

#include <stdexcept>

namespace vkfuse::core {

void gather_line(const LineGather& g, std::span<const double> in, std::span<double> out, bool accumulate) {
    if (int(out.size()) != g.outputs) throw std::logic_error("gather_line: output length");
    for (int i = 0; i < g.outputs; ++i) {
        const int* idx = &g.index[std::size_t(i) * g.taps];
        const double* w = &g.weight[std::size_t(i) * g.taps];
        double sum = 0;
        for (int t = 0; t < g.taps; ++t) sum += w[t] * in[idx[t]];
        out[i] = accumulate ? out[i] + sum : sum;
    }
}

void gather_axis_add(const Plane& in, int axis, const LineGather& g, Plane& out) {
    if (axis == 1) {
        if (out.height != in.height || out.width != g.outputs) throw std::logic_error("gather_axis: shape");
        for (int y = 0; y < in.height; ++y) {
            const std::span<const double> src(&in.data[std::size_t(y) * in.width], std::size_t(in.width));
            gather_line(g, src, std::span<double>(&out.data[std::size_t(y) * out.width], std::size_t(out.width)),
                        true);
        }
        return;
    }
    if (out.width != in.width || out.height != g.outputs) throw std::logic_error("gather_axis: shape");
    for (int i = 0; i < g.outputs; ++i) {
        double* dst = &out.data[std::size_t(i) * out.width];
        for (int t = 0; t < g.taps; ++t) {
            const double w = g.weight[std::size_t(i) * g.taps + t];
            const double* src = &in.data[std::size_t(g.index[std::size_t(i) * g.taps + t]) * in.width];
            for (int x = 0; x < in.width; ++x) dst[x] += w * src[x];
        }
    }
}

Plane gather_axis(const Plane& in, int axis, const LineGather& g) {
    Plane out = axis == 0 ? Plane(g.outputs, in.width) : Plane(in.height, g.outputs);
    gather_axis_add(in, axis, g, out);
    return out;
}

}  // namespace vkfuse::core

// The per-coefficient fusion rules.
#include "core/rules.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vkfuse::core {
namespace {

double max_abs(std::span<const double> v) {
    double best = v[0];
    for (std::size_t k = 1; k < v.size(); ++k)
        if (std::abs(v[k]) > std::abs(best)) best = v[k];  // strict: ties keep the earlier frame
    return best;
}

double mean(std::span<const double> v) {
    double sum = 0;
    for (double x : v) sum += x;
    return sum / double(v.size());
}

}  // namespace

double combine(Rule rule, std::span<const double> values) {
    if (values.empty()) throw std::invalid_argument("combine: no values");
    switch (rule) {
        case Rule::MaxAbs: return max_abs(values);
        case Rule::Mean: return mean(values);
        case Rule::Max: return *std::max_element(values.begin(), values.end());
        case Rule::Min: return *std::min_element(values.begin(), values.end());
    }
    throw std::invalid_argument("combine: invalid rule enumerator");
}

Plane combine_planes(Rule rule, std::span<const Plane* const> planes) {
    if (planes.empty()) throw std::invalid_argument("combine_planes: no planes");
    Plane out(planes[0]->height, planes[0]->width);
    for (const Plane* p : planes)
        if (!p->same_shape(out)) throw std::logic_error("combine_planes: shapes differ");
    std::vector<double> values(planes.size());
    for (std::size_t i = 0; i < out.data.size(); ++i) {
        for (std::size_t k = 0; k < planes.size(); ++k) values[k] = planes[k]->data[i];
        out.data[i] = combine(rule, values);
    }
    return out;
}

}  // namespace vkfuse::core

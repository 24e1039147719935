#include "cell.hpp"

namespace vkfuse::bench {

FusionSpec Cell::fusion() const {
    FusionSpec spec;
    spec.method = method.method;
    spec.wavelet = method.wavelet;
    spec.levels = levels;
    return spec;
}

bool Cell::same_workload(const Cell& o) const {
    return method == o.method && levels == o.levels && size == o.size && frames == o.frames && sensors == o.sensors;
}

std::string Cell::precision_name() const {
    return backend == Backend::Cpu ? "fp64" : std::string(to_string(precision));
}

std::string Cell::describe() const {
    std::string out = label(method);
    if (levels > 0) out += " L" + std::to_string(levels);
    out += " " + short_size_name(size) + " K" + std::to_string(frames) + " S" + std::to_string(sensors) + " " +
           std::string(to_string(backend));
    return precision == Precision::Fp32 ? out : out + " " + std::string(to_string(precision));
}

}  // namespace vkfuse::bench

#include "result.hpp"

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

std::optional<double> CellResult::bandwidth_fraction() const {
    if (!bytes_per_cycle || !copy_bandwidth || *copy_bandwidth <= 0 || timing.median_ms <= 0) return std::nullopt;
    return *bytes_per_cycle / (timing.median_ms * 1e-3) / *copy_bandwidth;
}

namespace {

// A peer runs one sensor; a cell of S sensors costs it S of those cycles.
std::optional<double> cell_ms(const std::optional<PeerResult>& peer, int sensors) {
    if (!peer || !peer->failure.empty()) return std::nullopt;
    return peer->per_sensor.median_ms * sensors;
}

}  // namespace

std::optional<double> CellResult::peer_cell_ms() const { return cell_ms(peer, cell.sensors); }
std::optional<double> CellResult::cpp_peer_cell_ms() const { return cell_ms(cpp_peer, cell.sensors); }

std::optional<double> CellResult::peer_speedup() const {
    const auto p = peer_cell_ms();
    if (!p || timing.median_ms <= 0 || !measured()) return std::nullopt;
    return *p / timing.median_ms;
}

std::optional<double> CellResult::cpp_peer_speedup() const {
    const auto p = cpp_peer_cell_ms();
    if (!p || timing.median_ms <= 0 || !measured()) return std::nullopt;
    return *p / timing.median_ms;
}

std::optional<double> CellResult::floor_fraction() const {
    if (!floor_ms || !measured() || timing.median_ms <= 0) return std::nullopt;
    return *floor_ms / timing.median_ms;
}

}  // namespace vkfuse::bench

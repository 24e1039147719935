#include "result.hpp"

namespace vkfuse::bench {

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

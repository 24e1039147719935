#include <algorithm>
#include <optional>
#include <string>

#include "report.hpp"

namespace vkfuse::bench {

namespace {

std::string cell_name(const Cell& c) {
    std::string name = label(c.method);
    return c.levels > 0 ? name + " L" + std::to_string(c.levels) : name;
}

std::string fmt(const char* format, double v) {
    char text[32];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

// A peer's time for the cell and how many times slower it is than the cell.
std::string peer_columns(std::optional<double> ms, std::optional<double> speedup) {
    return (ms ? fmt("%10.2f", *ms) : std::string(9, ' ') + "-") + " " +
           (speedup ? fmt("%8.2fx", *speedup) : std::string(8, ' ') + "-");
}

}  // namespace

void print_table_header(std::FILE* out) {
    // peer: the Python pipeline; c++: the OpenCV C++ one; floor: floor_ms / median_ms.
    std::fprintf(out, "%-22s %-6s %-4s %-6s %2s %3s %9s %9s %9s %5s %9s %8s %9s %9s %9s %6s %6s %10s %9s %10s %9s %8s %5s\n",
                 "method", "backend", "prec", "size", "K", "S", "median_ms", "min_ms", "max_ms", "runs", "sensor/s", "Mpix/s",
                 "max|err|", "mean|err|", "metric_re", ">1e-5", "bw%", "peer_ms", "peer/this", "c++_ms", "c++/this",
                 "floor_ms", "floor");
}

void print_row(std::FILE* out, const CellResult& r) {
    const Cell& c = r.cell;
    std::fprintf(out, "%-22s %-6s %-4s %-6s %2d %3d ", cell_name(c).c_str(), std::string(to_string(c.backend)).c_str(),
                 c.precision_name().c_str(), short_size_name(c.size).c_str(), c.frames, c.sensors);
    if (!r.measured()) {
        std::fprintf(out, "%s\n", (c.skip.empty() ? "failed: " + r.failure : "skipped: " + c.skip).c_str());
        return;
    }
    const auto bw = r.bandwidth_fraction();
    const auto floor = r.floor_fraction();
    std::fprintf(out, "%9.2f %9.2f %9.2f %4d%s %9.2f %8.2f %9.2e %9.2e %9.2e %6zu %6s %s %s %s\n", r.timing.median_ms,
                 r.timing.min_ms, r.timing.max_ms, r.timing.runs, r.timing.capped ? "*" : " ", r.throughput(),
                 r.mpixels_per_second(), r.error.max_abs, r.error.mean_abs(), r.metric_error.worst(),
                 r.error.over_tolerance, bw ? fmt("%5.2f%%", 100 * *bw).c_str() : "-",
                 peer_columns(r.peer_cell_ms(), r.peer_speedup()).c_str(),
                 peer_columns(r.cpp_peer_cell_ms(), r.cpp_peer_speedup()).c_str(),
                 floor ? (fmt("%8.2f", *r.floor_ms) + fmt(" %5.2f", *floor)).c_str() : "       -     -");
    if (r.stages.empty()) return;
    std::string line = "    stages (median ms):";
    for (const auto& s : r.stages) line += " " + s.name + fmt(" %.2f", s.median_ms);
    std::fprintf(out, "%s\n", line.c_str());
}

void print_peer(std::FILE* out, const PeerResult& p) {
    if (!p.failure.empty()) {
        std::fprintf(out, "    peer failed: %s\n", p.failure.c_str());
        return;
    }
    std::fprintf(out, "    peer %s: %.2f ms/sensor (median of %d, min %.2f, max %.2f), max|err| %.2e, mean|err| %.2e, metric_re %.2e\n",
                 p.name.c_str(), p.per_sensor.median_ms, p.per_sensor.runs, p.per_sensor.min_ms, p.per_sensor.max_ms,
                 p.error.max_abs, p.error.mean_abs(), p.metric_error.worst());
}

namespace {

// fp16 storage has no tolerance to meet (docs/spec.md): its error is reported.
void print_fp16(std::FILE* out, const std::vector<CellResult>& results) {
    for (const auto& r : results)
        if (r.cell.precision == Precision::Fp16Storage && r.measured())
            std::fprintf(out, "fp16 storage: %s: max|err| %.2e, mean|err| %.2e, metric rel err %.2e\n",
                         r.cell.describe().c_str(), r.error.max_abs, r.error.mean_abs(), r.metric_error.worst());
}

void print_accuracy(std::FILE* out, const std::vector<CellResult>& results) {
    int measured = 0;
    const CellResult* worst = nullptr;
    for (const auto& r : results) {
        if (r.cell.backend != Backend::Vulkan || r.cell.precision != Precision::Fp32 || !r.measured()) continue;
        ++measured;
        if (!worst || r.error.max_abs > worst->error.max_abs) worst = &r;
        if (r.error.max_abs > kFusedTolerance || r.metric_error.worst() > kFusedTolerance)
            std::fprintf(out,
                         "  over 1e-5: %s: max|err| %.2e in %zu of %zu samples, metric rel err %.2e "
                         "(%.2e on its own fused image)\n",
                         r.cell.describe().c_str(), r.error.max_abs, r.error.over_tolerance, r.error.samples,
                         r.metric_error.worst(), r.metric_error_own_image.worst());
    }
    if (worst)
        std::fprintf(out, "accuracy: %d vulkan fp32 cells, worst max|err| %.2e (%s)\n", measured, worst->error.max_abs,
                     worst->cell.describe().c_str());
    if (worst && worst->error.over_tolerance > 0)
        std::fprintf(out,
                     "  max-abs near-ties are the known source of samples over 1e-5: where two frames' coefficients "
                     "differ in magnitude by less than float rounding, float and double may pick different frames "
                     "(the mean/max/min rules stay below 1e-6 on the same frames).\n");
}

// Sensor-cycles per second at S > 1 over the same workload at S = 1, from the
// medians and from the fastest runs (the latter suffers less when other
// processes share the host).
void print_batching(std::FILE* out, const std::vector<CellResult>& results) {
    for (const auto& one : results) {
        if (one.cell.backend != Backend::Vulkan || one.cell.sensors != 1 || !one.measured()) continue;
        std::string line;
        for (const auto& many : results) {
            Cell as_one = many.cell;
            as_one.sensors = 1;
            if (many.cell.backend != Backend::Vulkan || many.cell.sensors == 1 || !many.measured() ||
                many.cell.precision != one.cell.precision || !as_one.same_workload(one.cell))
                continue;
            const double by_min = (many.cell.sensors / many.timing.min_ms) / (1.0 / one.timing.min_ms);
            char part[96];
            std::snprintf(part, sizeof part, " S=%d %.2fx (fastest runs %.2fx)", many.cell.sensors,
                          many.throughput() / one.throughput(), by_min);
            line += part;
        }
        if (!line.empty())
            std::fprintf(out, "batching (vulkan sensor-cycles/s vs S=1): %s:%s\n", one.cell.describe().c_str(), line.c_str());
    }
}

}  // namespace

void print_summary(std::FILE* out, const std::vector<CellResult>& results) {
    std::fprintf(out, "\n");
    print_accuracy(out, results);
    print_fp16(out, results);
    print_batching(out, results);
    if (std::any_of(results.begin(), results.end(), [](const CellResult& r) { return r.timing.capped; }))
        std::fprintf(out, "runs marked * were cut below --runs by --cell-seconds (slow cycles on a CPU).\n");
}

}  // namespace vkfuse::bench

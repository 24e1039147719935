#include "report_summary.hpp"

#include <algorithm>

namespace vkfuse::bench {
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

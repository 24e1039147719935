// Sharpness, RMS contrast and background difference in one pass
// (shaders/metrics.comp): per workgroup a partial of 8 floats written into the
// read-back buffer, finished on the host in double by Plan::metrics.
#include <algorithm>
#include <cmath>

#include "vk/engine/magnitude.hpp"
#include "vk/passes/graph.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {
// metrics.comp: kGroupSize invocations per group (checked against its SPIR-V
// where it is dispatched: the read-back of one partial per group is sized by
// it), each a strip kRows tall and 4 pixels wide.
constexpr std::uint32_t kGroupSize = 256, kRows = VKFUSE_METRIC_ROWS;

std::uint64_t metric_items(const PlanConfig& cfg) {
    return groups(std::uint64_t(cfg.width), 4) * groups(std::uint64_t(cfg.height), kRows);
}

}  // namespace

std::uint32_t metric_groups(const PlanConfig& cfg) { return groups(metric_items(cfg), kGroupSize); }

bool metrics_write_image(const PlanConfig& cfg) { return !cfg.metrics.empty() && cfg.width % 4 == 0; }

void record_metrics(GraphBuilder& g, VkDeviceAddress fused, VkDeviceAddress background, DeviceSpan partials,
                    std::optional<DeviceSpan> image, std::uint32_t background_group) {
    const std::uint32_t wgs = metric_groups(g.cfg);
    if (g.rec.local_size("metrics")[0] != kGroupSize)
        throw Error(ErrorKind::Device, "internal: metrics.comp's local size is not the " + std::to_string(kGroupSize) +
                                           " its partials are sized by");
    const DeviceSpan img = g.span(fused), bg = background ? g.span(background) : img;
    const DeviceSpan out = image ? *image : partials;
    g.rec.dispatch("metrics", {img, img, bg, bg, partials, out, out},
                   PushConstants()
                       .i32("width", g.cfg.width)
                       .i32("height", g.cfg.height)
                       .u32("channels", std::uint32_t(g.cfg.channels))
                       .u32("groups", wgs)
                       .u32("has_bg", background ? 1 : 0)
                       .u32("want_sharpness", g.cfg.metrics.has(Metric::Sharpness))
                       .u32("want_contrast", g.cfg.metrics.has(Metric::Contrast))
                       .u32("quads", g.cfg.width % 4 == 0)
                       .u32("pixels", std::uint32_t(g.cfg.width) * std::uint32_t(g.cfg.height))
                       .u32("write_image", image.has_value())
                       .u32("bg_group", background_group),
                   Recorder::LinearWork{metric_items(g.cfg), std::uint32_t(g.cfg.sensors)});
    g.rec.mark("metrics");
}

// float16 planes hold magnitudes up to 65504; beyond that a plane sample
// becomes Inf and the results Inf or NaN. Inputs in [0, 1] stay far inside at
// any level count, so this is checked where results are read, not on every
// input sample: a non-finite result of an fp16 plan is that overflow. A
// float32 plan keeps its values inside float's range by scaling
// (vk/engine/magnitude.hpp), so one there is an overflow the scaling missed: an
// error, never a NaN, Inf or JSON null handed on.
void check_device_results(const PlanConfig& cfg, const std::string& owner, std::span<const float> results,
                          const char* what) {
    const std::size_t bad = first_non_finite(results.data(), results.size());
    if (bad == results.size()) return;
    if (cfg.precision == Precision::Fp16Storage)
        throw Error(ErrorKind::Numeric, owner + ": a value left float16's range (65504) in a precision fp16 plan; "
                                                "fuse this input with Precision::Fp32");
    throw Error(ErrorKind::Numeric, owner + ": " + what + " overflowed float32 on the device (" +
                                        (std::isnan(results[bad]) ? "NaN" : "Inf") + ")");
}

Metrics finish_metrics(std::span<const float> partials, const PlanConfig& cfg, int exponent, const std::string& owner) {
    check_device_results(cfg, owner, partials, "a metric sum");
    // The workgroups' partials (shaders/metrics.comp) in double: the sums
    // added, the moments of the luma deviations combined pairwise (Chan).
    double sharpness = 0, background_diff = 0, count = 0, mean = 0, m2 = 0;
    for (std::size_t g = 0; g + kMetricPartialFloats <= partials.size(); g += kMetricPartialFloats) {
        const float* p = partials.data() + g;
        sharpness += p[0];
        background_diff += p[1];
        const double n = p[2];
        if (n == 0) continue;
        const double total = count + n, delta = double(p[3]) - mean;
        mean += delta * n / total;
        m2 += double(p[4]) + delta * delta * count * n / total;
        count = total;
    }
    const double n = double(cfg.height) * cfg.width;
    Metrics m;
    const MetricSet& which = cfg.metrics;
    m.sharpness = which.has(Metric::Sharpness) ? std::ldexp(sharpness / n, exponent) : std::nan("");
    m.contrast = which.has(Metric::Contrast) ? std::ldexp(std::sqrt(std::max(0.0, m2) / n), exponent) : std::nan("");
    if (which.has(Metric::BackgroundDiff)) m.background_diff = std::ldexp(background_diff / (n * cfg.channels), exponent);
    return m;
}

}  // namespace vkfuse::vk

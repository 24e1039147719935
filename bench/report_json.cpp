#include "report_json.hpp"

#include <cstdio>

#include "io/atomic_write.hpp"
#include "json_writer.hpp"

namespace vkfuse::bench {
namespace {

std::string metric_errors_json(const MetricError& m) {
    return JsonObject()
        .number("sharpness", m.sharpness)
        .number("contrast", m.contrast)
        .number("background_diff", m.background_diff)
        .str();
}

std::string stages_json(const std::vector<StageTime>& stages) {
    JsonObject o;
    for (const auto& s : stages) o.number(s.name, s.median_ms);
    return o.str();
}

void add_identity(JsonObject& o, const CellResult& r) {
    const Cell& c = r.cell;
    o.text("method", to_string(c.method.method));
    if (c.method.method == Method::Wavelet)
        o.text("wavelet", to_string(c.method.wavelet));
    else
        o.null("wavelet");
    if (c.levels > 0)
        o.integer("levels", c.levels);
    else
        o.null("levels");
    o.text("backend", to_string(c.backend)).text("device", r.device).text("precision", to_string(c.precision));
    o.integer("width", c.size.width).integer("height", c.size.height).integer("frames", c.frames).integer("sensors", c.sensors);
    std::optional<std::string> skipped;
    if (!c.skip.empty()) skipped = "skipped: " + c.skip;
    if (!r.failure.empty()) skipped = "failed: " + r.failure;
    o.text_or_null("skipped", skipped);
}

void add_measurements(JsonObject& o, const CellResult& r) {
    const bool m = r.measured();
    auto when = [m](double v) { return m ? std::optional<double>(v) : std::nullopt; };
    o.number_or_null("median_ms", when(r.timing.median_ms)).number_or_null("min_ms", when(r.timing.min_ms));
    o.number_or_null("max_ms", when(r.timing.max_ms)).number_or_null("runs", when(r.timing.runs)).boolean("runs_capped", r.timing.capped);
    o.number_or_null("plan_ms", r.cell.backend == Backend::Vulkan ? when(r.plan_ms) : std::nullopt);
    o.number_or_null("throughput_cycles_s", when(r.throughput())).number_or_null("mpixels_s", when(r.mpixels_per_second()));
    o.number_or_null("max_abs_err", when(r.error.max_abs)).number_or_null("mean_abs_err", when(r.error.mean_abs()));
    o.number_or_null("samples_over_1e-5", when(double(r.error.over_tolerance))).number_or_null("checked_sensors", when(r.checked_sensors));
    if (m) {
        o.raw("metric_rel_err", metric_errors_json(r.metric_error));
        o.raw("metric_rel_err_own_image", metric_errors_json(r.metric_error_own_image));
    } else {
        o.null("metric_rel_err").null("metric_rel_err_own_image");
    }
    if (m && !r.stages.empty())
        o.raw("kernel_ms", stages_json(r.stages));
    else
        o.null("kernel_ms");
    o.number_or_null("bytes_per_cycle", m ? r.bytes_per_cycle : std::nullopt);
    o.number_or_null("copy_bandwidth_gbs", r.copy_bandwidth ? std::optional<double>(*r.copy_bandwidth * 1e-9) : std::nullopt);
    o.number_or_null("bandwidth_fraction", m ? r.bandwidth_fraction() : std::nullopt);
    o.number_or_null("load_average", when(r.load_average));
}

void add_peer(JsonObject& o, const CellResult& r) {
    const PeerResult* p = r.peer && r.peer->failure.empty() ? &*r.peer : nullptr;
    o.text_or_null("peer", p ? std::optional<std::string>(p->name) : std::nullopt);
    o.text_or_null("peer_failure", r.peer && !r.peer->failure.empty() ? std::optional<std::string>(r.peer->failure) : std::nullopt);
    o.number_or_null("peer_median_ms", r.peer_cell_ms());
    o.number_or_null("peer_ms_per_sensor", p ? std::optional<double>(p->per_sensor.median_ms) : std::nullopt);
    o.number_or_null("peer_runs", p ? std::optional<double>(p->per_sensor.runs) : std::nullopt);
    o.number_or_null("peer_max_abs_err", p ? std::optional<double>(p->error.max_abs) : std::nullopt);
    o.number_or_null("peer_mean_abs_err", p ? std::optional<double>(p->error.mean_abs()) : std::nullopt);
    if (p)
        o.raw("peer_metric_rel_err", metric_errors_json(p->metric_error));
    else
        o.null("peer_metric_rel_err");
    o.number_or_null("peer_speedup", r.peer_speedup());
}

}  // namespace

const std::vector<std::string>& json_required_fields() {
    static const std::vector<std::string> fields{
        "method", "wavelet", "levels", "backend", "device", "precision", "width", "height", "frames", "sensors",
        "skipped", "median_ms", "min_ms", "max_ms", "runs", "throughput_cycles_s", "mpixels_s", "max_abs_err",
        "mean_abs_err", "samples_over_1e-5", "metric_rel_err", "kernel_ms", "bytes_per_cycle", "copy_bandwidth_gbs",
        "bandwidth_fraction", "peer", "peer_median_ms", "peer_max_abs_err", "peer_speedup"};
    return fields;
}

std::string cell_json(const CellResult& r) {
    JsonObject o;
    add_identity(o, r);
    add_measurements(o, r);
    add_peer(o, r);
    return o.str();
}

void write_json(const std::string& path, const std::vector<CellResult>& results) {
    std::string text = "[\n";
    for (std::size_t i = 0; i < results.size(); ++i) text += "  " + cell_json(results[i]) + (i + 1 < results.size() ? ",\n" : "\n");
    text += "]\n";
    io::write_atomically(path, [&](std::FILE* f) { std::fwrite(text.data(), 1, text.size(), f); });
}

}  // namespace vkfuse::bench

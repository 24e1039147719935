#include "report.hpp"

#include <cstdio>

#include "io/atomic_write.hpp"
#include "io/json_value.hpp"

namespace vkfuse::bench {
namespace {

using json::Value;

// A JSON object under construction, members in the order added.
class Members {
public:
    Members& add(std::string key, Value v) {
        object_.emplace_back(std::move(key), std::move(v));
        return *this;
    }
    Members& add(std::string key, std::optional<double> v) { return add(std::move(key), v ? Value(*v) : Value(nullptr)); }
    Members& add(std::string key, const std::optional<std::string>& v) {
        return add(std::move(key), v ? Value(*v) : Value(nullptr));
    }
    Value done() { return Value(std::move(object_)); }

private:
    Value::Object object_;
};

Value metric_errors(const MetricError& m) {
    return Members()
        .add("sharpness", Value(m.sharpness))
        .add("contrast", Value(m.contrast))
        .add("background_diff", Value(m.background_diff))
        .done();
}

Value stages(const std::vector<StageTime>& stages) {
    Members o;
    for (const auto& s : stages) o.add(s.name, Value(s.median_ms));
    return o.done();
}

std::optional<std::string> text_if(bool present, std::string_view text) {
    return present ? std::optional<std::string>(std::string(text)) : std::nullopt;
}

void add_identity(Members& o, const CellResult& r) {
    const Cell& c = r.cell;
    o.add("method", Value(std::string(to_string(c.method.method))));
    o.add("wavelet", text_if(c.method.has_wavelet(), to_string(c.method.wavelet)));
    o.add("levels", c.levels > 0 ? std::optional<double>(c.levels) : std::nullopt);
    o.add("backend", Value(std::string(to_string(c.backend)))).add("device", Value(r.device));
    o.add("driver", r.driver.empty() ? Value(nullptr) : Value(r.driver));
    o.add("precision", Value(c.precision_name()));
    o.add("width", Value(c.size.width)).add("height", Value(c.size.height));
    o.add("frames", Value(c.frames)).add("sensors", Value(c.sensors));
    std::optional<std::string> skipped;
    if (!c.skip.empty()) skipped = "skipped: " + c.skip;
    if (!r.failure.empty()) skipped = "failed: " + r.failure;
    o.add("skipped", skipped);
}

void add_measurements(Members& o, const CellResult& r) {
    const bool m = r.measured();
    auto when = [m](double v) { return m ? std::optional<double>(v) : std::nullopt; };
    o.add("median_ms", when(r.timing.median_ms)).add("min_ms", when(r.timing.min_ms));
    o.add("max_ms", when(r.timing.max_ms)).add("runs", when(r.timing.runs)).add("runs_capped", Value(r.timing.capped));
    o.add("plan_ms", r.cell.backend == Backend::Vulkan ? when(r.plan_ms) : std::nullopt);
    o.add("throughput_cycles_s", when(r.throughput())).add("mpixels_s", when(r.mpixels_per_second()));
    o.add("max_abs_err", when(r.error.max_abs)).add("mean_abs_err", when(r.error.mean_abs()));
    o.add("samples_over_1e-5", when(double(r.error.over_tolerance))).add("checked_sensors", when(r.checked_sensors));
    o.add("metric_rel_err", m ? metric_errors(r.metric_error) : Value(nullptr));
    o.add("metric_rel_err_own_image", m ? metric_errors(r.metric_error_own_image) : Value(nullptr));
    o.add("kernel_ms", m && !r.stages.empty() ? stages(r.stages) : Value(nullptr));
    o.add("bytes_per_cycle", m ? r.bytes_per_cycle : std::nullopt);
    o.add("copy_bandwidth_gbs", r.copy_bandwidth ? std::optional<double>(*r.copy_bandwidth * 1e-9) : std::nullopt);
    o.add("bandwidth_fraction", m ? r.bandwidth_fraction() : std::nullopt);
    o.add("kernel_copy_ns_per_float", r.kernel_copy_ns);
    o.add("cycle_fixed_ms", r.cycle_fixed_ms);
    o.add("floor_ms", m ? r.floor_ms : std::nullopt).add("floor_fraction", r.floor_fraction());
    o.add("load_average", when(r.load_average));
}

// One peer's fields, named `prefix`, `prefix`_median_ms, ...: "peer" for the
// Python pipeline, "cpp_peer" for the OpenCV C++ one.
void add_peer(Members& o, const std::string& prefix, const std::optional<PeerResult>& peer,
              std::optional<double> cell_ms, std::optional<double> speedup) {
    const PeerResult* p = peer && peer->failure.empty() ? &*peer : nullptr;
    auto peer_value = [p](double v) { return p ? std::optional<double>(v) : std::nullopt; };
    o.add(prefix, text_if(p, p ? p->name : ""));
    o.add(prefix + "_failure", text_if(peer && !peer->failure.empty(), peer ? peer->failure : ""));
    o.add(prefix + "_median_ms", cell_ms);
    o.add(prefix + "_ms_per_sensor", peer_value(p ? p->per_sensor.median_ms : 0));
    o.add(prefix + "_runs", peer_value(p ? p->per_sensor.runs : 0));
    o.add(prefix + "_max_abs_err", peer_value(p ? p->error.max_abs : 0));
    o.add(prefix + "_mean_abs_err", peer_value(p ? p->error.mean_abs() : 0));
    o.add(prefix + "_metric_rel_err", p ? metric_errors(p->metric_error) : Value(nullptr));
    o.add(prefix + "_speedup", speedup);
}

}  // namespace

const std::vector<std::string>& json_required_fields() {
    static const std::vector<std::string> fields{
        "method", "wavelet", "levels", "backend", "device", "driver", "precision", "width", "height", "frames", "sensors",
        "skipped", "median_ms", "min_ms", "max_ms", "runs", "throughput_cycles_s", "mpixels_s", "max_abs_err",
        "mean_abs_err", "samples_over_1e-5", "metric_rel_err", "kernel_ms", "bytes_per_cycle", "copy_bandwidth_gbs",
        "bandwidth_fraction", "kernel_copy_ns_per_float", "cycle_fixed_ms", "floor_ms", "floor_fraction", "peer", "peer_median_ms",
        "peer_max_abs_err", "peer_speedup", "cpp_peer", "cpp_peer_median_ms", "cpp_peer_max_abs_err", "cpp_peer_speedup"};
    return fields;
}

json::Value cell_json(const CellResult& r) {
    Members o;
    add_identity(o, r);
    add_measurements(o, r);
    add_peer(o, "peer", r.peer, r.peer_cell_ms(), r.peer_speedup());
    add_peer(o, "cpp_peer", r.cpp_peer, r.cpp_peer_cell_ms(), r.cpp_peer_speedup());
    return o.done();
}

void write_json(const std::string& path, const std::vector<CellResult>& results) {
    Value::Array cells;
    for (const auto& r : results) cells.push_back(cell_json(r));
    const std::string text = json::write(Value(std::move(cells))) + "\n";
    io::write_atomically(path, [&](std::FILE* f) { io::write_all(f, text, path); });
}

}  // namespace vkfuse::bench

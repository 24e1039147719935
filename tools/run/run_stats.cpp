#include "run/run_stats.hpp"

#include <algorithm>
#include <cstdio>

#include "standard_output.hpp"

namespace vkfuse::cli {
namespace {

std::string fixed(double v, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, v);
    return text;
}

std::string timing_json(const std::optional<SwitchTiming>& t, std::optional<double> window_bound) {
    if (!t) return "null";
    return "{\"frame_period_s\": " + json_number(t->frame_period) +
           ", \"latency_max_s\": " + json_number(t->latency_max) + ", \"clearance_s\": " + json_number(t->clearance) +
           ", \"delivery_s\": " + json_number(t->delivery) + ", \"jitter_s\": " + json_number(t->jitter) +
           ", \"window_bound_s\": " + json_number(window_bound.value_or(0)) + "}";
}

}  // namespace

RunStats::RunStats(std::size_t sensors, SkipConfig skip) : skip_(skip), sensors_(sensors) {}

void RunStats::add(const CycleResult& cycle, double write_s) {
    ++cycles_;
    last_ok_ = 0;
    for (std::size_t i = 0; i < cycle.sensors.size(); ++i) {
        const SensorCycle& s = cycle.sensors[i];
        if (s.status != SensorStatus::Ok) {
            errors_.insert(s.error);
            sensors_[i].last_error = s.error;
            continue;
        }
        ++last_ok_;
        ++fused_;
        if (s.skip.idle) ++idle_;
        fused_fraction_sum_ += s.skip.fused_fraction;
        PerSensor& p = sensors_[i];
        const double ts = s.newest_timestamp();
        if (p.fused++ == 0) p.first_ts = ts;
        p.last_ts = ts;
    }
    last_capture_s_ = cycle.capture_wait_s;
    last_fuse_s_ = cycle.fuse_s;
    last_write_s_ = write_s;
    capture_s_ += cycle.capture_wait_s;
    fuse_s_ += cycle.fuse_s;
    write_s_ += write_s;
}

double RunStats::wall_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double RunStats::sensor_elapsed_s() const {
    double widest = 0;
    for (const PerSensor& p : sensors_)
        if (p.fused > 0) widest = std::max(widest, p.last_ts - p.first_ts);
    return widest;
}

// Fused cycles per second of each sensor's own clock, from its first fused
// cycle to its last: what the LED schedule sustains, whatever the host speed.
std::vector<double> RunStats::sensor_clock_fps() const {
    std::vector<double> out;
    for (const PerSensor& p : sensors_)
        if (p.fused >= 2 && p.last_ts > p.first_ts) out.push_back(double(p.fused - 1) / (p.last_ts - p.first_ts));
    return out;
}

std::string RunStats::progress_line(std::optional<int> target) const {
    const double wall = std::max(wall_s(), 1e-9);
    const double per_s = double(fused_) / wall;
    return "cycle " + std::to_string(cycles_) + (target ? "/" + std::to_string(*target) : "") + " | " +
           std::to_string(last_ok_) + "/" + std::to_string(sensors_.size()) + " ok | " +
           fixed(per_s / double(sensors_.size()), 2) + " fused fps/sensor (" + fixed(per_s, 1) +
           " sensor-cycles/s) | capture " + fixed(last_capture_s_ * 1e3, 1) + " ms, fuse " +
           fixed(last_fuse_s_ * 1e3, 1) + " ms, write " + fixed(last_write_s_ * 1e3, 1) + " ms";
}

std::string RunStats::summary_json(const Rig& rig, const std::string& source) const {
    const double wall = std::max(wall_s(), 1e-9);
    const double n = double(std::max<std::uint64_t>(cycles_, 1));
    const std::vector<double> fps = sensor_clock_fps();
    double fps_min = 0, fps_mean = 0;
    if (!fps.empty()) {
        fps_min = *std::min_element(fps.begin(), fps.end());
        for (double f : fps) fps_mean += f / double(fps.size());
    }
    std::string timings, scheduling, held, errors;
    for (std::size_t i = 0; i < rig.sensors(); ++i) {
        const std::string key = (i ? ", " : "") + json_string(rig.serial(i)) + ": ";
        timings += key + timing_json(rig.timing(i), rig.window_bound(i));
        held += key + std::to_string(rig.windows_held(i));
        scheduling += key + json_string(rig.switch_scheduling(i));
    }
    for (const std::string& e : errors_) errors += (errors.empty() ? "" : ", ") + json_string(e);
    return "{\"cycles\": " + std::to_string(cycles_) + ", \"sensors\": " + std::to_string(sensors_.size()) +
           ", \"submits\": " + std::to_string(rig.submits()) + ", \"fused\": " + std::to_string(fused_) +
           ", \"wall_s\": " + json_number(wall) + ", \"sensor_cycles_per_s\": " + json_number(double(fused_) / wall) +
           ", \"fused_fps_per_sensor\": " + json_number(double(fused_) / wall / double(sensors_.size())) +
           ", \"sensor_clock_fps_min\": " + json_number(fps_min) +
           ", \"sensor_clock_fps_mean\": " + json_number(fps_mean) +
           ", \"cycles_in_flight\": " + std::to_string(rig.cycles_in_flight()) +
           ", \"window\": " + json_string(std::string(to_string(rig.window()))) + ", \"windows_held\": {" + held + "}" + ", \"ms_per_cycle\": {\"capture\": " + json_number(capture_s_ / n * 1e3) +
           ", \"fuse\": " + json_number(fuse_s_ / n * 1e3) + ", \"write\": " + json_number(write_s_ / n * 1e3) +
           "}, \"skip\": {\"mode\": " + json_string(std::string(to_string(skip_.policy))) +
           ", \"threshold\": " + json_number(skip_.threshold) +
           ", \"idle_fraction\": " + json_number(double(idle_) / double(std::max<std::uint64_t>(fused_, 1))) +
           ", \"fused_fraction\": " + json_number(fused_ ? fused_fraction_sum_ / double(fused_) : 1.0) +
           "}, \"switch_timing\": {" + timings + "}, \"switch_scheduling\": {" + scheduling + "}" + source + ", \"errors\": [" + errors + "]}";
}

}  // namespace vkfuse::cli

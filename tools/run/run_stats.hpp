// run_stats.hpp - throughput and per-stage latency of a `vkfuse run`, for the
// live progress line and the closing summary.
#pragma once
#include <chrono>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "vkfuse/rig/rig.hpp"

namespace vkfuse::cli {

class RunStats {
public:
    RunStats(std::size_t sensors, SkipConfig skip);

    void add(const CycleResult& cycle, double write_s);
    std::uint64_t cycles() const { return cycles_; }
    std::uint64_t fused() const { return fused_; }  // sensor-cycles fused from fresh frames
    std::uint64_t fused(std::size_t sensor) const { return sensors_.at(sensor).fused; }
    // The last error the sensor reported ("" when none).
    const std::string& last_error(std::size_t sensor) const { return sensors_.at(sensor).last_error; }
    const std::set<std::string>& errors() const { return errors_; }
    // Sensor time the fused frames span so far (the widest over sensors).
    double sensor_elapsed_s() const;

    // "cycle 57/120 | 16/16 ok | 3.1 fused fps/sensor (49.8 sensor-cycles/s) | capture 12 ms, fuse 80 ms, write 30 ms"
    std::string progress_line(std::optional<int> target) const;
    // One JSON object: counts, submits, throughput (wall clock and sensor
    // clock), mean stage latency, skipping (the policy, and the shares of
    // sensor-cycles idle and of tiles fused), each sensor's switch timing,
    // distinct errors.
    // source: members that say where the frames came from (", \"source\": {...}"), or "".
    std::string summary_json(const Rig& rig, const std::string& source = "") const;

private:
    struct PerSensor {
        std::uint64_t fused = 0;
        double first_ts = 0, last_ts = 0;
        std::string last_error;
    };
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    SkipConfig skip_;
    std::uint64_t cycles_ = 0, fused_ = 0, idle_ = 0;
    double fused_fraction_sum_ = 0;
    std::size_t last_ok_ = 0;
    double capture_s_ = 0, fuse_s_ = 0, write_s_ = 0;  // totals
    double last_capture_s_ = 0, last_fuse_s_ = 0, last_write_s_ = 0;
    std::vector<PerSensor> sensors_;
    std::set<std::string> errors_;

    double wall_s() const;
    std::vector<double> sensor_clock_fps() const;
};

}  // namespace vkfuse::cli

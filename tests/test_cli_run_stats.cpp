// RunStats (tools/run/run_stats.hpp), what `vkfuse run` reports in summary.json
// and its progress line, from synthetic cycles: frame timestamps on each
// sensor's clock and stage times chosen here, so every rate the summary
// derives from them is known exactly. Wall-clock rates are checked against
// the wall time the summary itself reports.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "run/run_stats.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::test {
namespace {

using cli::RunStats;

// The number after "key": in a JSON text (the first occurrence), as written
// (%.17g round-trips exactly).
double number_at(const std::string& json, const std::string& key) {
    const std::string tag = "\"" + key + "\": ";
    const std::size_t at = json.find(tag);
    if (at == std::string::npos) {
        ADD_FAILURE() << "no " << key << " in " << json;
        return NAN;
    }
    return std::strtod(json.c_str() + at + tag.size(), nullptr);
}

std::string serial(int i) { return "SIM-000" + std::to_string(i + 1); }

// A rig of three simulated sensors, never started: summary_json reads its
// serials, (absent) timings and submit count.
std::unique_ptr<Rig> idle_rig() {
    std::vector<RigSensor> sensors;
    for (int i = 0; i < 3; ++i) {
        SimDigitOptions o;
        o.serial = serial(i);
        o.clock = make_virtual_clock();
        sensors.push_back({std::make_shared<SimDigit>(o), o.clock});
    }
    RigConfig cfg;
    cfg.sequence = parse_sequence("15,15,15+0,15,0");
    return std::make_unique<Rig>(nullptr, cfg, sensors);
}

SensorCycle ok(int sensor, double last_ts) {
    SensorCycle s;
    s.serial = serial(sensor);
    Frame first, last;
    first.timestamp = last_ts - 1.0 / 30;
    last.timestamp = last_ts;
    s.frames = {first, last};
    return s;
}

SensorCycle not_ok(int sensor, SensorStatus status, const std::string& error) {
    SensorCycle s;
    s.serial = serial(sensor);
    s.status = status;
    s.error = error;
    return s;
}

// Six cycles of three sensors, each on its own clock:
//  - SIM-0001 fused every cycle, last frames at 1.0 + 0.1 c: 5 intervals in
//    0.5 s, 10 fused cycles per second of its clock;
//  - SIM-0002 timed out in cycle 2, fused in the others at 2.0 + 0.04 c: 5
//    fused cycles from 2.0 to 2.2, 4 intervals in 0.2 s = 20 per second (a
//    missed cycle is not an interval of its own);
//  - SIM-0003 fused cycles 0 and 1 at 0.5 and 0.75 (4 per second), then failed.
// Capture waits 10, 20, ..., 60 ms; every fuse 20 ms; writes 0, 5, ..., 25 ms.
struct Synthetic {
    RunStats stats{3, SkipConfig{SkipPolicy::Idle, 6.5}};
    std::vector<CycleResult> cycles;
    Synthetic() {
        for (int c = 0; c < 6; ++c) {
            CycleResult r;
            r.cycle = std::uint64_t(c);
            r.sensors.push_back(ok(0, 1.0 + 0.1 * c));
            if (c >= 3) r.sensors.back().skip = {true, false, 0.0, 0.0, 1.5, {}};  // SIM-0001 idle from cycle 3
            r.sensors.push_back(c == 2 ? not_ok(1, SensorStatus::Timeout, "SIM-0002: no frames within 5 s")
                                       : ok(1, 2.0 + 0.04 * c));
            r.sensors.push_back(c < 2 ? ok(2, 0.5 + 0.25 * c)
                                      : not_ok(2, SensorStatus::Failed, "SIM-0003: USB transfer failed"));
            r.capture_wait_s = 0.010 * (c + 1);
            r.fuse_s = 0.020;
            stats.add(r, 0.005 * c);
        }
    }
};

TEST(CliRunStats, CountsAndSensorClockRates) {
    Synthetic run;
    EXPECT_EQ(run.stats.cycles(), 6u);
    EXPECT_EQ(run.stats.fused(), 6u + 5u + 2u);
    EXPECT_EQ(run.stats.errors(),
              (std::set<std::string>{"SIM-0002: no frames within 5 s", "SIM-0003: USB transfer failed"}));
    EXPECT_NEAR(run.stats.sensor_elapsed_s(), 0.5, 1e-12);  // the widest span: SIM-0001's

    const auto rig = idle_rig();
    const std::string json = run.stats.summary_json(*rig);
    EXPECT_EQ(number_at(json, "cycles"), 6);
    EXPECT_EQ(number_at(json, "sensors"), 3);
    EXPECT_EQ(number_at(json, "submits"), 0);
    EXPECT_EQ(number_at(json, "fused"), 13);
    EXPECT_NEAR(number_at(json, "sensor_clock_fps_min"), 4.0, 1e-9) << json;
    EXPECT_NEAR(number_at(json, "sensor_clock_fps_mean"), (10.0 + 20.0 + 4.0) / 3, 1e-9) << json;
    EXPECT_NEAR(number_at(json, "capture"), (10 + 20 + 30 + 40 + 50 + 60) / 6.0, 1e-9) << json;  // ms per cycle
    EXPECT_NEAR(number_at(json, "fuse"), 20.0, 1e-9) << json;
    EXPECT_NEAR(number_at(json, "write"), (0 + 5 + 10 + 15 + 20 + 25) / 6.0, 1e-9) << json;
    EXPECT_NE(json.find("\"skip\": {\"mode\": \"idle\", \"threshold\": 6.5"), std::string::npos) << json;
    EXPECT_NEAR(number_at(json, "idle_fraction"), 3.0 / 13, 1e-12) << json;
    EXPECT_NEAR(number_at(json, "fused_fraction"), 10.0 / 13, 1e-12) << json;
    EXPECT_NE(json.find("\"errors\": [\"SIM-0002: no frames within 5 s\", \"SIM-0003: USB transfer failed\"]"),
              std::string::npos)
        << json;
    EXPECT_NE(json.find("\"switch_timing\": {\"SIM-0001\": null, \"SIM-0002\": null, \"SIM-0003\": null}"),
              std::string::npos)
        << json;
}

// The wall-clock rates: sensor-cycles fused per wall second, and that per
// sensor, consistent with the wall time reported beside them, which lies
// within the stats' lifetime.
TEST(CliRunStats, WallClockRatesFollowFromTheReportedWallTime) {
    const auto before = std::chrono::steady_clock::now();
    Synthetic run;
    const auto rig = idle_rig();
    const std::string json = run.stats.summary_json(*rig);
    const double lifetime = std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
    const double wall = number_at(json, "wall_s");
    EXPECT_GT(wall, 0.0);
    EXPECT_LE(wall, lifetime);
    EXPECT_NEAR(number_at(json, "sensor_cycles_per_s"), 13.0 / wall, 1e-12 * 13.0 / wall) << json;
    EXPECT_NEAR(number_at(json, "fused_fps_per_sensor"), 13.0 / wall / 3.0, 1e-12 * 13.0 / wall) << json;
}

TEST(CliRunStats, ProgressLineShowsTheLastCycle) {
    Synthetic run;
    const std::string line = run.stats.progress_line(10);
    EXPECT_EQ(line.rfind("cycle 6/10 | 2/3 ok | ", 0), 0u) << line;
    EXPECT_NE(line.find("| capture 60.0 ms, fuse 20.0 ms, write 25.0 ms"), std::string::npos) << line;
    EXPECT_EQ(run.stats.progress_line(std::nullopt).rfind("cycle 6 | 2/3 ok | ", 0), 0u);
}

// One sensor fused once: no interval, so no sensor-clock rate; the rates over
// no sensor with two fused cycles are 0, not NaN or Inf.
TEST(CliRunStats, NoRateFromASingleFusedCycle) {
    RunStats stats(3, SkipConfig{});
    CycleResult r;
    r.sensors = {ok(0, 1.0), not_ok(1, SensorStatus::Timeout, "SIM-0002: late"),
                 not_ok(2, SensorStatus::Timeout, "SIM-0003: late")};
    stats.add(r, 0.0);
    const auto rig = idle_rig();
    const std::string json = stats.summary_json(*rig);
    EXPECT_EQ(number_at(json, "sensor_clock_fps_min"), 0.0) << json;
    EXPECT_EQ(number_at(json, "sensor_clock_fps_mean"), 0.0) << json;
    EXPECT_EQ(stats.sensor_elapsed_s(), 0.0);
}

}  // namespace
}  // namespace vkfuse::test

#include "run/run_sensors.hpp"

#include <algorithm>
#include <cstdio>

#include "run/paced_sensor.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {

RunSensors simulated_sensors(const RunOptions& o) {
    RunSensors out;
    const std::shared_ptr<Clock> shared_real = o.virtual_clock ? nullptr : make_real_clock();
    for (int i = 0; i < o.sensors; ++i) {
        SimDigitOptions sim;
        sim.seed = std::uint64_t(i) + 1;
        const bool presses = i < o.pressing.value_or(o.sensors);
        sim.object = o.background_frames > 0 || !presses ? "nothing" : o.object;
        sim.camera_auto = o.camera_auto;
        sim.motion = o.motion;
        sim.motion_period_s = o.motion_period_s;
        char serial[16];
        std::snprintf(serial, sizeof serial, "SIM-%04d", i + 1);
        sim.serial = serial;
        // Virtual clocks are per sensor: each capture thread advances its own
        // sensor's time, so sensors never wait on one another's clock.
        sim.clock = o.virtual_clock ? make_virtual_clock() : shared_real;
        auto digit = std::make_shared<SimDigit>(sim);
        out.sims.push_back(digit);
        out.rig.push_back({digit, sim.clock});
    }
    return out;
}

RunSensors digit_sensors(const RunOptions& o, const std::vector<std::string>& devices) {
    RunSensors out;
    for (const std::string& device : devices) {
        DigitOptions digit;
        digit.device = device;
        digit.mode.encoding = o.encoding;
        std::shared_ptr<DigitSensor> sensor;
        try {
            sensor = std::make_shared<DigitSensor>(digit);
        } catch (const Error& e) {
            throw Error(e.kind(), "--sensor " + std::string(e.what()));
        }
        for (const RigSensor& r : out.rig)
            if (r.sensor->info().serial == sensor->info().serial)
                throw Error(ErrorKind::InvalidArgument, "--sensor " + device + ": names DIGIT " +
                                                            sensor->info().serial + " a second time");
        out.rig.push_back({sensor, sensor->clock()});
    }
    return out;
}

std::vector<std::string> plugged_digits() {
    std::vector<std::string> serials;
    for (const DigitDevice& d : find_digits())
        if (!d.bootloader && !d.serial.empty() && !d.video_nodes.empty()) serials.push_back(d.serial);
    return serials;
}

RunSensors replayed_sensors(const RunOptions& o, std::shared_ptr<const Dataset> dataset) {
    RunSensors out;
    out.judging = FrameJudging::Label;
    for (const DatasetSensorRecord& record : dataset->sensors) {
        auto sensor = std::make_shared<DatasetSensor>(dataset, record.info.serial, o.object);
        const std::size_t cycles = sensor->cycles_available(o.sequence);
        out.recorded_cycles = std::min(out.recorded_cycles.value_or(cycles), cycles);
        if (o.realtime) {
            sensor->preload();  // the pace is the recording's, never the decoder's
            auto paced = std::make_shared<PacedSensor>(sensor);
            out.rig.push_back({paced, paced});
        } else {
            out.rig.push_back({sensor, nullptr});
        }
    }
    return out;
}

void report_as_recorded(CycleResult& cycle, const Dataset& dataset) {
    for (SensorCycle& s : cycle.sensors) {
        if (s.status == SensorStatus::Ok) continue;
        for (const DatasetSensorRecord& r : dataset.sensors) {
            if (r.info.serial != s.serial) continue;
            for (const DatasetMiss& m : r.missed)
                if (m.cycle == std::int64_t(cycle.cycle)) {
                    s.status = m.status == "failed" ? SensorStatus::Failed : SensorStatus::Timeout;
                    s.error = m.error;
                }
        }
    }
}

}  // namespace vkfuse::cli

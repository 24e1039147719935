// rig_support.hpp - simulated DIGITs set up for rig tests.
#pragma once
#include <cstdio>
#include <memory>
#include <vector>

#include "sensor_doubles.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::test {

struct SimRigSensor {
    std::shared_ptr<Clock> clock;
    std::shared_ptr<SimDigit> sim;
    std::shared_ptr<TruthLoggingSensor> logged;
};

// A simulated DIGIT on its own virtual clock, serial SIM-%04d of number, with
// its ground truth logged; the camera's exposure is locked, as a rig sets it.
inline SimRigSensor sim_sensor(int number, double latency_s, const std::string& object = "coin",
                               bool camera_auto = false, SimMotion motion = SimMotion::Still,
                               double motion_period_s = 2.0) {
    SimRigSensor s;
    s.clock = make_virtual_clock();
    SimDigitOptions o;
    o.seed = std::uint64_t(number);
    o.led_latency_s = latency_s;
    o.object = object;
    o.camera_auto = camera_auto;
    o.motion = motion;
    o.motion_period_s = motion_period_s;
    o.clock = s.clock;
    char serial[16];
    std::snprintf(serial, sizeof serial, "SIM-%04d", number);
    o.serial = serial;
    s.sim = std::make_shared<SimDigit>(o);
    s.logged = std::make_shared<TruthLoggingSensor>(s.sim);
    return s;
}

}  // namespace vkfuse::test

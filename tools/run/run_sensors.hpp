// run_sensors.hpp - the sensors `vkfuse run` drives: simulated DIGITs, or a
// recorded dataset played back.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "run/run_options.hpp"
#include "vkfuse/rig/rig.hpp"
#include "vkfuse/ros2/remote.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::cli {

struct RunSensors {
    std::vector<RigSensor> rig;
    std::vector<std::shared_ptr<SimDigit>> sims;  // empty when replaying
    FrameJudging judging = FrameJudging::Timing;
    std::optional<std::size_t> recorded_cycles;  // replay: full cycles every sensor holds
    std::shared_ptr<ros2::RemoteRig> remote;     // --source ros2: where the frames come from
};

// N simulated DIGITs, serials SIM-0001.., seeds 1.., with nothing pressed yet
// when backgrounds are to be taken (the rig presses the object afterwards).
// Each has its own virtual clock, or all share one real clock. The camera's
// exposure and white balance are locked unless options.camera_auto: a rig
// sets them fixed, or the camera would even out the very differences between
// LED settings that fusion feeds on (and settle for ~0.1 s after each switch).
RunSensors simulated_sensors(const RunOptions& options);

// One DigitSensor per entry of `devices` (serials or video nodes), each
// streaming options.encoding at QVGA 60 fps, frames on CLOCK_MONOTONIC.
// Throws Error naming "--sensor <device>" when one cannot be opened.
RunSensors digit_sensors(const RunOptions& options, const std::vector<std::string>& devices);

// The serials of the DIGITs plugged in that can stream (not in their bootloader).
std::vector<std::string> plugged_digits();

// One DatasetSensor per recorded sensor, playing options.object.
RunSensors replayed_sensors(const RunOptions& options, std::shared_ptr<const Dataset> dataset);

// --source ros2: the sensors of capture hosts in o.ros_domain (o.digits by
// serial, else the first host's), once their descriptions are heard (at most
// o.startup_timeout_s); their sequence and background count adopted into o.
RunSensors remote_sensors(RunOptions& o, const Args& args);

// With --source ros2, summary.json's account of what each sensor's capture
// host sent (", \"source\": {...}"); otherwise "".
std::string source_summary(const RunSensors& sensors);

// A replayed sensor that delivered nothing in a cycle in which the recorded
// run also got nothing from it gets the recorded status and message, so the
// replay reports what the recording did.
void report_as_recorded(CycleResult& cycle, const Dataset& dataset);

}  // namespace vkfuse::cli

// run_session.hpp - what `vkfuse run` drives, opened from its options: the
// sensors (real DIGITs, simulated ones, a replayed dataset or a capture host
// on ROS 2's wire) and the rig's configuration. The Python module's
// vkfuse.Rig opens its rig here too, from the same options, so the two take
// the same sensors with the same defaults and checks.
#pragma once
#include <memory>
#include <optional>

#include "args.hpp"
#include "run/run_options.hpp"
#include "run/run_sensors.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::cli {

struct RigSession {
    RunOptions options;
    std::shared_ptr<const Dataset> dataset;  // with --replay
    RunSensors sensors;
};

// Opens s.options' sources (options parsed by parse_run_options(args)):
// --source ros2, --replay (its recording adopted into s.options and its
// memory checked), the DIGITs named or plugged in, else simulated DIGITs (a
// choice made without being asked for is said in one line on stderr).
// Throws Error naming the option.
void open_sources(RigSession& s, const Args& args);

// The rig's configuration for s: fused images read back only when written
// or published (want_fused), simulated DIGITs pressing their object once the
// background is taken. Recording and publishing callbacks are the caller's.
RigConfig rig_config(const RigSession& s);

// The cycles to run: --cycles, else every cycle a replay recorded, else none (until stopped).
std::optional<int> cycle_target(const RigSession& s);

}  // namespace vkfuse::cli

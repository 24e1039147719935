// `vkfuse run --source ros2`: a capture host's sensors as this rig's
// (vkfuse/ros2/remote.hpp); a vkfuse built without vkfuse::ros2 refuses the
// option while parsing (run_options.cpp).
#include "standard_output.hpp"
#include "run/run_sensors.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {

#ifdef VKFUSE_WITH_ROS2
RunSensors remote_sensors(RunOptions& o, const Args& args) {
    ros2::RemoteRigOptions options;
    options.domain = o.ros_domain;
    options.serials = o.digits;
    options.startup_timeout_s = o.startup_timeout_s;
    options.queue_cycles = o.source_queue;
    RunSensors out;
    out.remote = std::make_shared<ros2::RemoteRig>(options);
    out.judging = FrameJudging::Label;
    out.rig = out.remote->sensors();
    const ros2::RemoteDescription& d = out.remote->description();
    adopt_remote(o, args, d.sequence, d.background_frames, int(d.sensors.size()));
    return out;
}

std::string source_summary(const RunSensors& s) {
    if (!s.remote) return "";
    std::string sensors;
    for (std::size_t i = 0; i < s.rig.size(); ++i) {
        const ros2::RemoteCounts c = s.remote->counts(i);
        sensors += (i ? ", " : "") + json_string(s.rig[i].sensor->info().serial) + ": {\"cycles\": " +
                   std::to_string(c.cycles) + ", \"missed\": " + std::to_string(c.missed) +
                   ", \"malformed\": " + std::to_string(c.malformed) + ", \"lost\": " + std::to_string(c.lost) + "}";
    }
    return ", \"source\": {\"kind\": \"ros2\", \"sensors\": {" + sensors + "}}";
}
#else
std::string source_summary(const RunSensors&) { return ""; }

RunSensors remote_sensors(RunOptions&, const Args&) {
    throw Error(ErrorKind::InvalidArgument, "--source ros2: this vkfuse was built without ROS 2 support");
}
#endif

}  // namespace vkfuse::cli

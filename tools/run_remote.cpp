// `vkfuse run --source ros2`: a capture host's sensors as this rig's
// (vkfuse/ros2/remote.hpp); a vkfuse built without vkfuse::ros2 refuses the
// option while parsing (run_options.cpp).
#include "run_sensors.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {

#ifdef VKFUSE_WITH_ROS2
RunSensors remote_sensors(RunOptions& o, const Args& args) {
    ros2::RemoteRigOptions options;
    options.domain = o.ros_domain;
    options.serials = o.digits;
    options.startup_timeout_s = o.startup_timeout_s;
    RunSensors out;
    out.remote = std::make_shared<ros2::RemoteRig>(options);
    out.judging = FrameJudging::Label;
    for (const std::shared_ptr<Sensor>& s : out.remote->sensors()) out.rig.push_back({s, nullptr});
    const ros2::RemoteDescription& d = out.remote->description();
    adopt_remote(o, args, d.sequence, d.background_frames, int(d.sensors.size()));
    return out;
}
#else
RunSensors remote_sensors(RunOptions&, const Args&) {
    throw Error(ErrorKind::InvalidArgument, "--source ros2: this vkfuse was built without ROS 2 support");
}
#endif

}  // namespace vkfuse::cli

// Looks for a capture host (vkfuse run --capture-only --publish ros2
// --publish-frames) in ROS domain argv[1] (default 0) for argv[2] seconds
// (default 1) and prints the sensors it describes, or why there are none.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"
#include "vkfuse/ros2/remote.hpp"

int main(int argc, char** argv) {
    vkfuse::ros2::RemoteRigOptions options;
    options.domain = argc > 1 ? std::atoi(argv[1]) : 0;
    options.startup_timeout_s = argc > 2 ? std::atof(argv[2]) : 1.0;
    try {
        const vkfuse::ros2::RemoteRig rig(options);
        for (const vkfuse::SensorInfo& s : rig.description().sensors)
            std::printf("%s on /vkfuse/%s: %dx%d\n", s.serial.c_str(), vkfuse::ros2::topic_token(s.serial).c_str(),
                        s.width, s.height);
        return 0;
    } catch (const vkfuse::Error& e) {
        std::printf("no capture host: %s\n", e.what());
        return e.kind() == vkfuse::ErrorKind::Timeout ? 0 : 1;
    }
}

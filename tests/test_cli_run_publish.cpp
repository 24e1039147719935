// `vkfuse run --publish ros2` and its options, refused before any work where
// they cannot hold: the one line, exit 2, nothing on stdout. (What a
// publishing run sends is tests/ros2, read through Fast DDS.)
#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace vkfuse::test {
namespace {

TEST(CliRunPublish, OptionsThatCannotHoldAreRefused) {
    for (const char* option : {"--publish-encoding", "--publish-wait"})
        expect_run_refused({option, "1"},
                           std::string("run: ") + option + " needs --publish ros2 (see 'vkfuse run --help')");
    expect_run_refused({"--publish-frames"}, "run: --publish-frames needs --publish ros2 (see 'vkfuse run --help')");
    expect_run_refused({"--ros-domain", "1"},
                       "run: --ros-domain needs --publish ros2 or --source ros2 (see 'vkfuse run --help')");
    expect_run_refused({"--publish", "zenoh"}, "--publish zenoh: expected ros2");
    expect_run_refused({"--source", "zenoh"}, "--source zenoh: expected ros2");
#ifdef VKFUSE_WITH_ROS2
    expect_run_refused({"--publish", "ros2", "--ros-domain", "233"}, "--ros-domain 233: expected a domain 0..232");
    expect_run_refused({"--publish", "ros2", "--ros-domain", "-1"}, "--ros-domain -1: expected a domain 0..232");
    expect_run_refused({"--publish", "ros2", "--publish-encoding", "bgr8"},
                       "--publish-encoding bgr8: expected rgb8 or 32FC3");
    // ROS_DOMAIN_ID is read as ROS 2 reads it, and checked the same way.
    const CliResult r = run_cli({"run", "--virtual-clock", "--cycles", "1", "--publish", "ros2"}, {"ROS_DOMAIN_ID=7x"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "vkfuse: ROS_DOMAIN_ID=7x: expected a domain 0..232\n");
    EXPECT_TRUE(r.out.empty());
    // A capture host's cycles must go somewhere whole, and nothing of fusion applies to it.
    expect_run_refused({"--capture-only"}, "run: --capture-only: needs --publish ros2 --publish-frames or --record (the "
                                           "cycles would go nowhere) (see 'vkfuse run --help')");
    expect_run_refused({"--capture-only", "--publish", "ros2", "--publish-frames", "--skip", "idle"},
                       "run: --skip does not apply to --capture-only (nothing is fused) (see 'vkfuse run --help')");
    expect_run_refused({"--capture-only", "--record", "r", "--out", "o"},
                       "run: --capture-only: --out holds fused images, and nothing is fused (see 'vkfuse run --help')");
    // A fusion host takes what the capture host decided.
    auto source_refused = [](const std::vector<std::string>& extra, const std::string& message) {
        std::vector<std::string> args{"run", "--source", "ros2"};
        args.insert(args.end(), extra.begin(), extra.end());
        const CliResult r = run_cli(args);
        EXPECT_EQ(r.status, 2) << message;
        EXPECT_EQ(r.err, "vkfuse: run: " + message + " (see 'vkfuse run --help')\n");
        EXPECT_TRUE(r.out.empty());
    };
    for (const char* option : {"--sequence", "--background-frames", "--replay"})
        source_refused({option, "x"}, std::string(option) + " does not apply to --source ros2 (the capture host decides)");
    source_refused({"--sensors", "2"}, "--sensors does not apply to --source ros2 (its sensors are another host's)");
    source_refused({"--publish", "ros2", "--publish-frames"},
                   "--publish-frames does not apply to --source ros2 (the capture host publishes the frames)");
#else
    expect_run_refused({"--publish", "ros2"},
                       "--publish ros2: this vkfuse was built without ROS 2 support (Cyclone DDS: apt-get install "
                       "cyclonedds-dev cyclonedds-tools, then build again)");
    expect_run_refused({"--source", "ros2"},
                       "--source ros2: this vkfuse was built without ROS 2 support (Cyclone DDS: apt-get install "
                       "cyclonedds-dev cyclonedds-tools, then build again)");
#endif
}

}  // namespace
}  // namespace vkfuse::test

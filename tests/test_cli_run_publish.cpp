// `vkfuse run --publish ros2` and its options, refused before any work where
// they cannot hold: the one line, exit 2, nothing on stdout. (What a
// publishing run sends is tests/ros2, read through Fast DDS.)
#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace vkfuse::test {
namespace {

TEST(CliRunPublish, OptionsThatCannotHoldAreRefused) {
    for (const char* option : {"--ros-domain", "--publish-encoding", "--publish-wait"})
        expect_run_refused({option, "1"},
                           std::string("run: ") + option + " needs --publish ros2 (see 'vkfuse run --help')");
    expect_run_refused({"--publish", "zenoh"}, "--publish zenoh: expected ros2");
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
#else
    expect_run_refused({"--publish", "ros2"},
                       "--publish ros2: this vkfuse was built without ROS 2 support (Cyclone DDS: apt-get install "
                       "cyclonedds-dev cyclonedds-tools, then build again)");
#endif
}

}  // namespace
}  // namespace vkfuse::test

// sensor/ros2_schema.hpp - ROS 2 message definitions as MCAP's "ros2msg"
// schemas: a type's .msg text, then each type it uses, once, after a line of
// 80 '=' and "MSG: <package>/<Type>" (rosbag2's form, which ros2 bag, the
// MCAP tools and Foxglove parse).
#pragma once
#include <string>
#include <string_view>

namespace vkfuse::sensor {

// "vkfuse_msgs/msg/RecordedFrame" (or "vkfuse_msgs/RecordedFrame") -> its
// schema. Throws Error(InvalidArgument) for a type vkfuse does not carry.
std::string ros2msg_schema(std::string_view type);

}  // namespace vkfuse::sensor

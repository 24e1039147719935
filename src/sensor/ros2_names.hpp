// sensor/ros2_names.hpp - how a serial becomes one token of a ROS 2 name
// (vkfuse/ros2/publisher.hpp's topic_token, which MCAP recordings share).
#pragma once
#include <string>
#include <string_view>

namespace vkfuse::sensor {

// Letters, digits and underscores, no leading digit: every other character
// becomes '_', and a leading digit gets "sensor_" before it.
std::string ros2_topic_token(std::string_view serial);

}  // namespace vkfuse::sensor

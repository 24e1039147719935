// ROS 2 names, domains and encodings (vkfuse/ros2/publisher.hpp).
#include <string>

#include "sensor/ros2_names.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"

namespace vkfuse::ros2 {

std::string topic_token(std::string_view serial) { return sensor::ros2_topic_token(serial); }

}  // namespace vkfuse::ros2

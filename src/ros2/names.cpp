// ROS 2 names, domains and encodings (vkfuse/ros2/publisher.hpp).
#include <string>

#include "core/method_table.hpp"
#include "sensor/ros2_names.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"

namespace vkfuse::ros2 {

std::string topic_token(std::string_view serial) { return sensor::ros2_topic_token(serial); }

std::string method_label(const FusionSpec& fusion) {
    std::string label(to_string(fusion.method));
    if (core::method_info(fusion.method).uses_wavelet) label += "/" + std::string(to_string(fusion.wavelet));
    return label;
}

}  // namespace vkfuse::ros2

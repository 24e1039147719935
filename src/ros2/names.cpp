// ROS 2 names, domains and encodings (vkfuse/ros2/publisher.hpp).
#include <cctype>
#include <string>

#include "core/method_table.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"

namespace vkfuse::ros2 {

std::string topic_token(std::string_view serial) {
    std::string token;
    for (char c : serial) token += std::isalnum(static_cast<unsigned char>(c)) && c >= 0 ? c : '_';
    if (token.empty() || std::isdigit(static_cast<unsigned char>(token[0]))) token = "sensor_" + token;
    return token;
}

std::string method_label(const FusionSpec& fusion) {
    std::string label(to_string(fusion.method));
    if (core::method_info(fusion.method).uses_wavelet) label += "/" + std::string(to_string(fusion.wavelet));
    return label;
}

}  // namespace vkfuse::ros2

#include "sensor/ros2_names.hpp"

#include <cctype>

namespace vkfuse::sensor {

std::string ros2_topic_token(std::string_view serial) {
    std::string token;
    for (char c : serial) token += std::isalnum(static_cast<unsigned char>(c)) && c >= 0 ? c : '_';
    if (token.empty() || std::isdigit(static_cast<unsigned char>(token[0]))) token = "sensor_" + token;
    return token;
}

}  // namespace vkfuse::sensor

#include "json.hpp"

#include <cmath>
#include <cstdio>

#include "io/json_value.hpp"

namespace vkfuse::cli {

std::string json_string(std::string_view text) { return json::quote(text); }

std::string json_number(double value) {
    if (!std::isfinite(value)) return "null";
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

}  // namespace vkfuse::cli

// json.hpp - the two JSON values vkfuse metrics prints.
#pragma once
#include <string>
#include <string_view>

namespace vkfuse::cli {

// A quoted JSON string: '"' and '\' escaped, control characters as \uXXXX,
// bytes that are not well-formed UTF-8 as \ufffd (json::quote).
std::string json_string(std::string_view text);

// %.17g, which round-trips every double; JSON has no NaN or Inf, so those are null.
std::string json_number(double value);

}  // namespace vkfuse::cli

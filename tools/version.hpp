// version.hpp - what `vkfuse --version` prints.
#pragma once
#include <string_view>

namespace vkfuse::cli {

// Keep in step with project(vkfuse VERSION ...) in CMakeLists.txt.
inline constexpr std::string_view kVersion = "0.1.0";

}  // namespace vkfuse::cli

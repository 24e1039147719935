// The SPIR-V of every kernel, compiled at build time and embedded here.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vkfuse::vk {

// SPIR-V words of shaders/<name>.comp; throws Error if there is no such shader.
std::span<const std::uint32_t> shader_spirv(const std::string& name);
// Whether a shader (variant) of that name is embedded.
bool has_shader(const std::string& name);
// Every embedded shader (variant), in build order.
std::vector<std::string> shader_names();

}  // namespace vkfuse::vk

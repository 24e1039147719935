// Asking a kernel to keep float32 subnormals (SPIR-V's DenormPreserve
// execution mode, Vulkan 1.2's shaderFloatControls).
//
// A GPU may flush float32 subnormals to zero unless a module asks otherwise,
// and Plan's magnitude scaling (vk/engine/magnitude.hpp) lets frames far below their
// background reach the kernels near 2^-64, where the squares that contrast
// and background difference sum fall under 2^-126. CPU devices (lavapipe)
// keep subnormals anyway and may not offer the mode; GPUs that do
// (shaderDenormPreserveFloat32) get every kernel patched as it is built.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace vkfuse::vk {

// The module with OpCapability DenormPreserve, the SPV_KHR_float_controls
// extension where its SPIR-V version predates 1.4, and OpExecutionMode
// DenormPreserve 32 for each entry point. A module that already declares the
// mode comes back unchanged. Throws Error(Internal) on words that are not a
// well-formed module.
std::vector<std::uint32_t> preserving_subnormals(std::span<const std::uint32_t> spirv);

}  // namespace vkfuse::vk

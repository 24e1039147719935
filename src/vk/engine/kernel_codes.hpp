// The codes the kernels share with the C++ side (shaders/kernel_codes.h),
// checked here against the enums they mirror: an enum reordered without the
// kernels fails to compile.
#pragma once
#include <cstdint>

#include "../../../shaders/kernel_codes.h"  // beside the kernels that include it too
#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/skip.hpp"

namespace vkfuse::vk {

static_assert(std::uint32_t(Rule::MaxAbs) == VKFUSE_RULE_MAX_ABS);
static_assert(std::uint32_t(Rule::Mean) == VKFUSE_RULE_MEAN);
static_assert(std::uint32_t(Rule::Max) == VKFUSE_RULE_MAX);
static_assert(std::uint32_t(Rule::Min) == VKFUSE_RULE_MIN);

static_assert(kSkipTile == VKFUSE_SKIP_TILE);

// A rule as the kernels read it.
constexpr std::uint32_t rule_code(Rule r) { return std::uint32_t(r); }

}  // namespace vkfuse::vk

// Whether the device's fma is fused (one rounding), which compensated float32
// filters (shaders/compensated.glsl) rely on for each product's error. Vulkan
// promises fma only the precision of a separate multiply and add, so the
// context asks the device once, before it builds a compensated kernel.
#pragma once

#include "vk/engine/context_impl.hpp"

namespace vkfuse::vk {

// Runs probe_fma_error on pairs whose products are inexact in float and
// compares each result with the exact rounding error (computed in double,
// where a product of two floats is exact). true only when every one matches:
// a device that fuses some fmas and not others gets the split too.
bool fma_is_fused(Context::Impl& ctx);

}  // namespace vkfuse::vk

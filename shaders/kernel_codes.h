// Codes that the kernels and the C++ side share, declared once: included by
// shaders/common.glsl and by src/vk/kernel_codes.hpp, which static_asserts
// each against the C++ enum it mirrors. Plain #defines, so that both GLSL and
// C++ read this file as it is.
#ifndef VKFUSE_KERNEL_CODES_H
#define VKFUSE_KERNEL_CODES_H

// Fusion rules (docs/spec.md "Rules"): the values of vkfuse::Rule.
#define VKFUSE_RULE_MAX_ABS 0u
#define VKFUSE_RULE_MEAN 1u
#define VKFUSE_RULE_MAX 2u
#define VKFUSE_RULE_MIN 3u

// pointwise_fuse.comp's `method`: which per-pixel fusion it runs.
#define VKFUSE_POINTWISE_BROVEY 0u
#define VKFUSE_POINTWISE_CHANNEL_SUM 1u
#define VKFUSE_POINTWISE_MEAN 2u  // the background model's mean of K frames

#endif

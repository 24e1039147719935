// Codes that the kernels and the C++ side share, declared once: included by
// shaders/common.glsl and by src/vk/engine/kernel_codes.hpp, which static_asserts
// each against the C++ enum it mirrors. Plain #defines, so that both GLSL and
// C++ read this file as it is.
#ifndef VKFUSE_KERNEL_CODES_H
#define VKFUSE_KERNEL_CODES_H

// Fusion rules (docs/spec.md "Rules"): the values of vkfuse::Rule.
#define VKFUSE_RULE_MAX_ABS 0u
#define VKFUSE_RULE_MEAN 1u
#define VKFUSE_RULE_MAX 2u
#define VKFUSE_RULE_MIN 3u

// pointwise_fuse.comp's METHOD (a specialization constant): which per-pixel fusion it runs.
#define VKFUSE_POINTWISE_BROVEY 0u
#define VKFUSE_POINTWISE_CHANNEL_SUM 1u
#define VKFUSE_POINTWISE_MEAN 2u  // the background model's mean of K frames

// What one invocation of a kernel covers, which the C++ side sizes its
// dispatches (and the skip tiles their scores) by.
#define VKFUSE_PYR_DOWN_ROWS 8       // pyr_down(4).comp: output rows per invocation
#define VKFUSE_LAP_FUSE_ROWS 2       // lap_fuse_collapse4.comp: coarse rows per invocation
#define VKFUSE_METRIC_ROWS 16        // metrics.comp: rows of an invocation's strip 4 pixels wide
#define VKFUSE_LINE_GROUP 64         // invocations per group of the 1-D pyramid and wavelet kernels (common.glsl grid_item)
#define VKFUSE_CONV_BLOCK 8          // filter_taps.glsl: outputs per invocation of a wavelet convolution
#define VKFUSE_ROW_PAIRS 8           // dwt_row_pairs.glsl: coefficient pairs per invocation of a row pass of quads
#define VKFUSE_COMPOSE_SPAN 32       // sparse_compose.comp: pixels of a row per invocation
#define VKFUSE_GATHER_WORDS 16       // skip_gather.comp: words per invocation
#define VKFUSE_SKIP_TILE 32          // change_detect.comp: a skip tile's side (vkfuse::kSkipTile)

// filter_taps.glsl's specialization constants take constant_ids 0 .. 40 (F,
// then 4 x 10 taps); a kernel's own constants come after them.
#define VKFUSE_FILTER_CONSTANTS 41

#endif

// Shared declarations for every vkfuse kernel. A kernel's buffers are declared
// in its own BUFFERS list (bindings.glsl).
//
// Planes: what a plan keeps on the device between kernels (unpacked frames,
// pyramid levels, wavelet coefficients, fused planes), as plane_t samples or
// plane4_t quads. Each kernel is built as float32, and with
// VKFUSE_FP16_STORAGE defined, where planes hold float16 and half the bytes
// (PlanConfig::precision). Arithmetic is float32 in both; TO_PLANE() and
// TO_PLANE4() round a result to the storage type. Uploads, backgrounds, metric
// partials and read-back stay float32.
//
// float16 is storage only: loads and stores convert, no arithmetic is done in
// float16 (the explicit-arithmetic extension only lets loads convert
// implicitly), so the modules declare 16-bit storage and not the Float16
// capability, and the device needs storageBuffer16BitAccess, not
// shaderFloat16 (a test checks every module). How a float rounds to
// float16 is the device's choice; where it rounds toward zero, an overflow
// would give 65504 instead of infinity and escape the non-finite check that
// turns it into Error(Numeric). So whatever rounds to infinity under
// round-to-nearest (|x| >= 65520) is made infinite first, exactly.
#ifdef VKFUSE_FP16_STORAGE
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
const float kPlaneOverflow = 65520.0;
float overflow_to_inf(float x) { return abs(x) >= kPlaneOverflow ? x * uintBitsToFloat(0x7f800000u) : x; }
vec4 overflow_to_inf(vec4 x) {
    return mix(x, x * uintBitsToFloat(0x7f800000u), greaterThanEqual(abs(x), vec4(kPlaneOverflow)));
}
#define TO_PLANE(x) float16_t(overflow_to_inf(x))
#define plane_t float16_t
#define plane4_t f16vec4
#define TO_PLANE4(x) f16vec4(overflow_to_inf(x))
#else
#define TO_PLANE(x) (x)
#define plane_t float
#define plane4_t vec4
#define TO_PLANE4(x) (x)
#endif

// Item index of a 1-D kernel of group_size invocations per group, dispatched
// as an (x, y) grid of workgroups (grid_1d() in recorder.hpp: x alone is
// limited to 65535 groups). The size is passed in because gl_WorkGroupSize is
// not yet declared where this file is included.
uint linear_index(uint group_size) {
    return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * group_size + gl_LocalInvocationID.x;
}

// Item (x, y) of such a kernel over a grid `width` items wide, x the faster.
// Kernels whose grids shrink level by level (pyramids, wavelet lines) run
// 1-D: a 2-D group of 16 x 16 leaves masked every lane past a small level's
// width or height, and lavapipe runs a masked lane at nearly full cost.
ivec2 grid_item(uint group_size, uint width) {
    uint i = linear_index(group_size);
    return ivec2(int(i % width), int(i / width));
}

// The fused sensor of a fusing kernel's slot (workgroup z / C). A cached
// fusion (study/cached_fusion.hpp) fuses sensors that come in blocks of
// `period`, one per source, and reaches each group of sources' coefficients
// through a dispatch of its own: slot i is member first + i % count of block
// i / count. A plan's dispatch covers every sensor (first 0, count = period).
uint group_sensor(uint slot, uint first, uint count, uint period) {
    return slot / count * period + first + slot % count;
}

// Index reflection about the first and last sample without repeating them
// (OpenCV BORDER_REFLECT_101, "whole-sample symmetric"): -1 -> 1, n -> n-2.
int reflect101(int i, int n) {
    if (n == 1) return 0;
    while (i < 0 || i >= n) i = i < 0 ? -i : 2 * (n - 1) - i;
    return i;
}

// Fusion rules (docs/spec.md "Rules"), applied to the K values of one
// coefficient; their codes are kernel_codes.h's.
#include "kernel_codes.h"
const uint RULE_MAX_ABS = VKFUSE_RULE_MAX_ABS;
const uint RULE_MEAN = VKFUSE_RULE_MEAN;
const uint RULE_MAX = VKFUSE_RULE_MAX;
const uint RULE_MIN = VKFUSE_RULE_MIN;

struct RuleState {
    float pick;  // max-abs / max / min: the value chosen so far
    float sum;   // mean: running sum in frame order
};

void rule_add(inout RuleState st, uint rule, uint k, float v) {
    if (rule == RULE_MEAN) {
        st.sum = k == 0u ? v : st.sum + v;
    } else if (k == 0u) {
        st.pick = v;
    } else if (rule == RULE_MAX_ABS) {
        if (abs(v) > abs(st.pick)) st.pick = v;  // strict: ties keep the lowest frame index
    } else if (rule == RULE_MAX) {
        st.pick = max(st.pick, v);
    } else {
        st.pick = min(st.pick, v);
    }
}

float rule_result(RuleState st, uint rule, uint frames) {
    return rule == RULE_MEAN ? st.sum / float(frames) : st.pick;
}

// The same for four neighbouring coefficients under one rule.
void rule_add4(uint rule, inout vec4 pick, inout vec4 sum, uint k, vec4 v) {
    if (rule == RULE_MEAN) {
        sum = k == 0u ? v : sum + v;
    } else if (k == 0u) {
        pick = v;
    } else if (rule == RULE_MAX_ABS) {
        pick = mix(pick, v, greaterThan(abs(v), abs(pick)));  // strict: ties keep the lowest frame
    } else if (rule == RULE_MAX) {
        pick = max(pick, v);
    } else {
        pick = min(pick, v);
    }
}

vec4 rule_result4(uint rule, uint frames, vec4 pick, vec4 sum) { return rule == RULE_MEAN ? sum / float(frames) : pick; }

// Shared declarations for every vkfuse kernel. Buffers are reached through
// device addresses carried in push constants, so no kernel needs descriptor
// sets: a Plan just records addresses and sizes.
#extension GL_EXT_buffer_reference : require

layout(buffer_reference, std430, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Words { uint v[]; };

// Planes: the buffers a plan keeps on the device between kernels (unpacked
// frames, pyramid levels, wavelet coefficients, fused planes). Each kernel is
// built twice: as float32, and with VKFUSE_FP16_STORAGE defined, where planes
// hold float16 and half the bytes (PlanConfig::precision). Arithmetic is
// float32 in both; TO_PLANE() rounds a result to the storage type. Uploads,
// backgrounds, metric partials and read-back stay Floats.
#ifdef VKFUSE_FP16_STORAGE
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
layout(buffer_reference, std430, buffer_reference_align = 2) buffer Planes { float16_t v[]; };
#define TO_PLANE(x) float16_t(x)
#define plane_t float16_t
#define plane4_t f16vec4
#define TO_PLANE4(x) f16vec4(x)
#else
#define Planes Floats
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

// Index reflection about the first and last sample without repeating them
// (OpenCV BORDER_REFLECT_101, "whole-sample symmetric"): -1 -> 1, n -> n-2.
int reflect101(int i, int n) {
    if (n == 1) return 0;
    while (i < 0 || i >= n) i = i < 0 ? -i : 2 * (n - 1) - i;
    return i;
}

// Fusion rules (SPEC.md "Rules"), applied to the K values of one coefficient.
const uint RULE_MAX_ABS = 0u;
const uint RULE_MEAN = 1u;
const uint RULE_MAX = 2u;
const uint RULE_MIN = 3u;

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

// cv::pyrUp at the 2 x 2 outputs (2i + a, 2j + b), a, b in {0, 1} (as
// out[a][b]), from the 3 x 3 source samples they all draw on: 9 loads for 4
// outputs. Per axis an even output weighs source samples (i - 1, i, i + 1) by
// (1, 6, 1)/8, an odd one (i, i + 1) by (4, 4)/8; the left/top border
// reflects (reflect-101), the right/bottom one repeats the last sample, a
// length-1 axis repeats its only sample (8/8): OpenCV's own edge handling.
// Horizontal sums per source row first, then the vertical combination, as
// OpenCV adds them.
float pyr_up_h(vec3 v, int parity, int n) {
    if (n == 1) return 8.0 * v.y;
    return parity == 0 ? (1.0 * v.x + 6.0 * v.y) + 1.0 * v.z : 4.0 * v.y + 4.0 * v.z;
}

mat2 pyr_up_block(Planes src, uint base, int sw, int sh, int i, int j) {
    // Source rows / columns: even outputs read (i - 1 reflected, i, i + 1
    // clamped), odd outputs (i, i + 1 clamped): the three cover both.
    ivec3 r = ivec3(i == 0 ? min(1, sh - 1) : i - 1, i, min(i + 1, sh - 1));
    ivec3 c = ivec3(j == 0 ? min(1, sw - 1) : j - 1, j, min(j + 1, sw - 1));
    vec3 h_even, h_odd;  // horizontal sums per source row for even / odd output columns
    for (int a = 0; a < 3; ++a) {
        uint row = base + uint(r[a] * sw);
        vec3 v = vec3(src.v[row + uint(c.x)], src.v[row + uint(c.y)], src.v[row + uint(c.z)]);
        h_even[a] = pyr_up_h(v, 0, sw);
        h_odd[a] = pyr_up_h(v, 1, sw);
    }
    mat2 out_;
    out_[0][0] = pyr_up_h(h_even, 0, sh) * (1.0 / 64.0);
    out_[0][1] = pyr_up_h(h_odd, 0, sh) * (1.0 / 64.0);
    out_[1][0] = pyr_up_h(h_even, 1, sh) * (1.0 / 64.0);
    out_[1][1] = pyr_up_h(h_odd, 1, sh) * (1.0 / 64.0);
    return out_;
}

// Compensated dot products (Ogita, Rump and Oishi's Dot2): each product's
// rounding error (through fma) and each addition's (Knuth's TwoSum) go into
// a second accumulator, so a filter output carries about twice float's
// precision and is rounded once. Arithmetic is cheap next to loads here; what
// it buys is that a rig re-fusing its own output (the stress suite's 100
// feedback passes) meets far smaller roundings per pass. `precise` keeps the
// compiler from reassociating the error terms away; where fma is not fused,
// the product error reads 0 and only the additions are compensated.
struct Dot2 {
    float sum;
    float err;
};

void dot2_add(inout Dot2 d, float a, float b) {
    precise float p = a * b;
    precise float product_err = fma(a, b, -p);
    precise float t = d.sum + p;
    precise float z = t - d.sum;
    precise float sum_err = (d.sum - (t - z)) + (p - z);
    d.sum = t;
    d.err += product_err + sum_err;
}

float dot2_result(Dot2 d) {
    precise float r = d.sum + d.err;
    return r;
}

// Shared declarations for every vkfuse kernel. Buffers are reached through
// device addresses carried in push constants, so no kernel needs descriptor
// sets: a Plan just records addresses and sizes.
#extension GL_EXT_buffer_reference : require

layout(buffer_reference, std430, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Words { uint v[]; };

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

// cv::pyrUp as a gather: output index o along an axis of source length n reads
// up to three source samples with weights out of 8. Left/top border reflects
// (reflect-101), right/bottom border repeats the last sample, a length-1 axis
// repeats its only sample: exactly OpenCV's own edge handling.
void pyr_up_taps(int o, int n, out ivec3 idx, out vec3 w) {
    if (n == 1) {
        idx = ivec3(0);
        w = vec3(8.0, 0.0, 0.0);
        return;
    }
    int i = o >> 1;
    if ((o & 1) == 0) {
        idx = ivec3(i == 0 ? 1 : i - 1, i, min(i + 1, n - 1));
        w = vec3(1.0, 6.0, 1.0);
    } else {
        idx = ivec3(i, min(i + 1, n - 1), 0);
        w = vec3(4.0, 4.0, 0.0);
    }
}

// pyrUp(src)(y, x) for the plane starting at base (sw x sh, tightly packed):
// horizontal sums per source row first, then the vertical combination, as OpenCV.
float pyr_up_at(Floats src, uint base, int sw, int sh, int y, int x) {
    ivec3 ri, ci;
    vec3 rw, cw;
    pyr_up_taps(y, sh, ri, rw);
    pyr_up_taps(x, sw, ci, cw);
    float acc = 0.0;
    for (int a = 0; a < 3; ++a) {
        if (rw[a] == 0.0) continue;
        uint row = base + uint(ri[a] * sw);
        float h = 0.0;
        for (int b = 0; b < 3; ++b)
            if (cw[b] != 0.0) h += cw[b] * src.v[row + uint(ci[b])];
        acc += rw[a] * h;
    }
    return acc * (1.0 / 64.0);
}

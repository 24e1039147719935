#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "reduce.glsl"
// Final pass of the hierarchical reduction: one workgroup per sensor adds that
// sensor's `groups` vec4 partials into one vec4.
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    Floats partials;
    Floats totals;  // vec4 per sensor
    uint groups;
} pc;

void main() {
    uint s = gl_WorkGroupID.z;
    precise vec4 sum = vec4(0.0), comp = vec4(0.0);
    for (uint g = gl_LocalInvocationIndex; g < pc.groups; g += WG) {
        uint o = (s * pc.groups + g) * 4u;
        kahan_add(sum, comp, vec4(pc.partials.v[o], pc.partials.v[o + 1u], pc.partials.v[o + 2u], pc.partials.v[o + 3u]));
    }
    vec4 total = workgroup_sum(sum, comp);
    if (gl_LocalInvocationIndex == 0u)
        for (uint i = 0u; i < 4u; ++i) pc.totals.v[s * 4u + i] = total[i];
}

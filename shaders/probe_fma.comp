#version 460
// Device probe (vk/probes/kernel_access.cpp): arithmetic rate. Each invocation runs
// ROUNDS steps y = y * x + 0.5 on four independent lanes, which converge to
// 0.5 / (1 - x) for |x| < 1, so the result can be checked.
layout(local_size_x = 256) in;
layout(std430, set = 0, binding = 0) readonly buffer Src { vec4 v[]; } src;
layout(std430, set = 0, binding = 1) writeonly buffer Dst { vec4 v[]; } dst;
layout(push_constant, std430) uniform Push {
    uvec4 unused;
    uint count;  // vec4 elements
} pc;
const int ROUNDS = 256;

void main() {
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
    if (i >= pc.count) return;
    vec4 x = src.v[i];
    vec4 y = vec4(0.0);
    for (int r = 0; r < ROUNDS; ++r) y = fma(y, x, vec4(0.5));
    dst.v[i] = y;
}

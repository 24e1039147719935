#version 460
// Device probe (vk/probes/kernel_access.cpp): the cost of exchanging values through
// workgroup shared memory. Every round each invocation stores its value,
// waits at a barrier, takes its right neighbour's (wrapping within the group)
// times 2, and waits again: what a tiled kernel pays to share its halo. After
// ROUNDS rounds invocation l holds 2^ROUNDS * src[group + (l + ROUNDS) % 256].
layout(local_size_x = 256) in;
layout(std430, set = 0, binding = 0) readonly buffer Src { float v[]; } src;
layout(std430, set = 0, binding = 1) writeonly buffer Dst { float v[]; } dst;
layout(push_constant, std430) uniform Push {
    uvec4 unused;
    uint count;  // a multiple of 256
} pc;
const uint ROUNDS = 8u;
shared float exchange[256];

void main() {
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
    uint l = gl_LocalInvocationID.x;
    // count is a multiple of 256: a group is wholly in or out, so every
    // invocation that reaches a barrier has its whole group with it.
    if ((i & ~255u) >= pc.count) return;
    float x = src.v[i];
    for (uint r = 0u; r < ROUNDS; ++r) {
        exchange[l] = x;
        barrier();
        x = 2.0 * exchange[(l + 1u) & 255u];
        barrier();
    }
    dst.v[i] = x;
}

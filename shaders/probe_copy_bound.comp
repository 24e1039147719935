#version 460
// Device probe (vk/probes/kernel_access.cpp): dst = 2 * src, one float per
// invocation, through descriptor-bound storage buffers.
layout(local_size_x = 256) in;
layout(std430, set = 0, binding = 0) readonly buffer Src { float v[]; } src;
layout(std430, set = 0, binding = 1) writeonly buffer Dst { float v[]; } dst;
layout(push_constant, std430) uniform Push {
    uvec4 unused;  // keeps `count` where probe_copy_address has it
    uint count;
} pc;

void main() {
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
    if (i < pc.count) dst.v[i] = 2.0 * src.v[i];
}

#version 460
// Device probe (vk/probes/kernel_access.cpp): dst = 2 * src, four floats per
// invocation, through descriptor-bound storage buffers.
layout(local_size_x = 256) in;
layout(std430, set = 0, binding = 0) readonly buffer Src { vec4 v[]; } src;
layout(std430, set = 0, binding = 1) writeonly buffer Dst { vec4 v[]; } dst;
layout(push_constant, std430) uniform Push {
    uvec4 unused;
    uint count;  // vec4 elements
} pc;

void main() {
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
    if (i < pc.count) dst.v[i] = 2.0 * src.v[i];
}

#version 460
// Device probe (vk/probes/kernel_access.cpp): dst = 2 * src, four floats per
// invocation, reached through device addresses.
#extension GL_EXT_buffer_reference : require
layout(local_size_x = 256) in;
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4s { vec4 v[]; };
layout(push_constant, std430) uniform Push {
    Vec4s src;
    Vec4s dst;
    uint count;  // vec4 elements
} pc;

void main() {
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
    if (i < pc.count) pc.dst.v[i] = 2.0 * pc.src.v[i];
}

#version 460
// Device probe (vk/probes/kernel_access.cpp): dst = 2 * src, one float per
// invocation, reached through device addresses as every vkfuse kernel
// reaches its buffers.
#extension GL_EXT_buffer_reference : require
layout(local_size_x = 256) in;
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(push_constant, std430) uniform Push {
    Floats src;
    Floats dst;
    uint count;
} pc;

void main() {
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
    if (i < pc.count) pc.dst.v[i] = 2.0 * pc.src.v[i];
}

#version 460
// Device probe (vk/probes/fma_probe.cpp): is fma fused? Each invocation writes
// fma(a, b, -a*b) for one pair: a product's exact rounding error where fma is
// fused (one rounding), 0 where it is a multiply and an add, which is all
// Vulkan promises. Compensated float32 filters (compensated.glsl) rely on the
// first and fall back to Dekker's split otherwise.
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer Pairs { vec2 v[]; } pairs;
layout(std430, set = 0, binding = 1) writeonly buffer Errors { float v[]; } errors;
layout(push_constant, std430) uniform Push {
    uint count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    vec2 ab = pairs.v[i];
    precise float p = ab.x * ab.y;
    precise float e = fma(ab.x, ab.y, -p);
    errors.v[i] = e;
}

// A kernel's buffers, declared once. Before including this file a kernel
// defines
//     #define BUFFERS(X) X(0, vec4, src) X(1, plane4, dst) ...
// one X(binding, element, name) per buffer, in binding order, and then puts
// BUFFER_FIELDS first in its push-constant block and reaches each buffer as
// BUF(name).v[i]. The kernel is built in two variants from that one list
// (CMakeLists.txt; Recorder::dispatch passes the buffers either way):
//  - bound (default): descriptor-bound storage buffers, set 0, binding b.
//  - VKFUSE_ADDRESSED: 64-bit device addresses at the start of the push
//    constants: on CPU devices (lavapipe, where the same kernels measured up
//    to a fifth faster this way), for kernels with more buffers than a stage may bind, and
//    for plans whose buffers exceed maxStorageBufferRange (KernelBuffers,
//    vkfuse/vk/context.hpp).
// Elements: float, vec4, uint, uvec4, and plane_t / plane4_t: a plane sample or
// four of them (float32, or float16 with VKFUSE_FP16_STORAGE: common.glsl).
#ifdef VKFUSE_ADDRESSED
#extension GL_EXT_buffer_reference : require
layout(buffer_reference, std430, buffer_reference_align = 4) buffer float_ref { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer vec4_ref { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer uint_ref { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer uvec4_ref { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 2) buffer plane_t_ref { plane_t v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer plane4_t_ref { plane4_t v[]; };
#define VKFUSE_ADDRESS_FIELD(b, element, name) element##_ref name;
#define BUFFER_FIELDS BUFFERS(VKFUSE_ADDRESS_FIELD)
#define BUF(name) pc.name
#else
#define VKFUSE_BINDING(b, element, name) \
    layout(std430, set = 0, binding = b) buffer name##_binding { element v[]; } name;
BUFFERS(VKFUSE_BINDING)
#define BUFFER_FIELDS
#define BUF(name) name
#endif

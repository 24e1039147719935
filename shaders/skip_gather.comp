#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// A skipping plan's compaction on the device (skip_decide.comp listed what
// moves): slot after slot (workgroup z), `words` words of src's slot into
// dst's slot, WORDS_PER_INVOCATION per invocation (256 apart, so that a
// workgroup reads one run of memory): on lavapipe a workgroup costs more
// than the few words it would otherwise copy. Fused sensor s takes slot j <= s, so moving the frames in
// place would let one slot's copy overwrite frames another has yet to read;
// they go through a scratch buffer instead, and only from the first slot g
// whose sensor is not its own (the slots before g hold theirs already):
//   mode 0: frames of sensor SENSOR_OF(g + z) -> scratch slot z
//   mode 1: scratch slot z -> frames slot g + z
//   mode 2: background of sensor SENSOR_OF(j) -> background slot j, j = COPY_LIST(z)
#define BUFFERS(X) X(0, uint, src) X(1, uint, dst) X(2, uint, decision)
#include "bindings.glsl"
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint sensors;
    uint words;  // a slot's
    uint mode;
} pc;
#include "skip_decision.glsl"

const uint WORDS_PER_INVOCATION = uint(VKFUSE_GATHER_WORDS);

void main() {
    uint first = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u * WORDS_PER_INVOCATION +
                 gl_LocalInvocationID.x;
    uint z = gl_WorkGroupID.z;
    if (first >= pc.words) return;
    uint g = BUF(decision).v[FIRST_MOVED], from, to;
    if (pc.mode == 0u) {
        from = BUF(decision).v[SENSOR_OF(g + z)];
        to = z;
    } else if (pc.mode == 1u) {
        from = z;
        to = g + z;
    } else {
        to = BUF(decision).v[COPY_LIST(z)];
        from = BUF(decision).v[SENSOR_OF(to)];
    }
    uint end = min(first + 256u * WORDS_PER_INVOCATION, pc.words);
    for (uint w = first; w < end; w += 256u) BUF(dst).v[to * pc.words + w] = BUF(src).v[from * pc.words + w];
}

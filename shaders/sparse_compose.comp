#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// The last pass of a tile-sparse wavelet fusion (sparse.glsl): in every slot
// fused sparsely, each pixel outside the rectangle the inverse computed (its
// record's lines = rows, blocks = columns, both circular) takes the fused
// background of the slot's sensor. Fully fused slots (full = 1) are left as
// they are. Invocation (x, y): SPAN pixels of row y from x SPAN; workgroup z:
// plane slot * C + c. A span per invocation reads its record once: on
// lavapipe, loading it per pixel cost more than the copy.
#define BUFFERS(X) X(0, plane_t, fused) X(1, float, background) X(2, uint, regions)
#include "bindings.glsl"
layout(local_size_x = 16, local_size_y = 16) in;
const int SPAN = VKFUSE_COMPOSE_SPAN;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint region;
    uint slot_planes;  // channels
    int width;
    int height;
} pc;
#include "sparse.glsl"

// Whether i lies in the circular range of count from start over n.
bool within(int i, int start, int count, int n) {
    int d = i - start;
    return (d < 0 ? d + n : d) < count;
}

void main() {
    int x0 = int(gl_GlobalInvocationID.x) * SPAN, y = int(gl_GlobalInvocationID.y);
    uint z = gl_WorkGroupID.z;
    if (x0 >= pc.width || y >= pc.height) return;
    uint at = sparse_record(z);
    if (BUF(regions).v[at + 6u] != 0u) return;
    bool row_inside = within(y, int(BUF(regions).v[at]), int(BUF(regions).v[at + 1u]), pc.height);
    int left = int(BUF(regions).v[at + 2u]), width = int(BUF(regions).v[at + 3u]);
    uint pixels = uint(pc.width * pc.height), row = uint(y * pc.width);
    uint sensor = BUF(regions).v[at + 5u], c = z - (z / pc.slot_planes) * pc.slot_planes;
    uint dst = z * pixels + row, src = (sensor * pc.slot_planes + c) * pixels + row;
    for (int x = x0; x < min(x0 + SPAN, pc.width); ++x)
        if (!row_inside || !within(x, left, width, pc.width))
            BUF(fused).v[dst + uint(x)] = TO_PLANE(BUF(background).v[src + uint(x)]);
}

#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// One step of Laplacian reconstruction, in place: C_l += pyrUp(R_{l+1}, size of C_l).
// An invocation takes the 2 x 2 outputs that share one 3 x 3 neighbourhood of
// R_{l+1} (pyr_up_block).
layout(local_size_x = VKFUSE_LINE_GROUP) in;
// coarse: R_{l+1}, cw x ch per plane; fine: C_l, width x height per plane,
// which becomes R_l.
#define BUFFERS(X) X(0, plane_t, coarse) X(1, plane_t, fine)
#include "bindings.glsl"
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int width;
    int height;
    int cw;
    int ch;
} pc;
#include "pyr_up.glsl"

void main() {
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), uint(pc.cw));
    int j = item.x, i = item.y;
    uint z = gl_WorkGroupID.z;
    if (j >= pc.cw || i >= pc.ch) return;
    mat2 up = pyr_up_block(z * uint(pc.cw * pc.ch), pc.cw, pc.ch, i, j);
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            int y = 2 * i + a, x = 2 * j + b;
            if (y >= pc.height || x >= pc.width) continue;
            uint at = z * uint(pc.width * pc.height) + uint(y * pc.width + x);
            BUF(fine).v[at] = TO_PLANE(up[a][b] + BUF(fine).v[at]);
        }
}

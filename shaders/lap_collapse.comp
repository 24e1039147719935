#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// One step of Laplacian reconstruction, in place: C_l += pyrUp(R_{l+1}, size of C_l).
layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, std430) uniform Push {
    Floats coarse;  // R_{l+1}, cw x ch per plane
    Floats fine;    // C_l, width x height per plane; becomes R_l
    int width;
    int height;
    int cw;
    int ch;
} pc;

void main() {
    int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    uint z = gl_WorkGroupID.z;
    if (x >= pc.width || y >= pc.height) return;
    uint i = z * uint(pc.width * pc.height) + uint(y * pc.width + x);
    pc.fine.v[i] = pyr_up_at(pc.coarse, z * uint(pc.cw * pc.ch), pc.cw, pc.ch, y, x) + pc.fine.v[i];
}

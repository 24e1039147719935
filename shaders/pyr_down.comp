#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// cv::pyrDown on every plane: 5x5 binomial [1 4 6 4 1]/16 per axis around
// source sample 2x (reflect-101 borders), output ((w+1)/2, (h+1)/2).
layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, std430) uniform Push {
    Floats src;
    Floats dst;
    int sw;
    int sh;
    int dw;
    int dh;
} pc;

const float K5[5] = float[5](1.0, 4.0, 6.0, 4.0, 1.0);

void main() {
    int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    uint z = gl_WorkGroupID.z;
    if (x >= pc.dw || y >= pc.dh) return;
    uint sbase = z * uint(pc.sw * pc.sh);
    int cols[5];
    for (int j = 0; j < 5; ++j) cols[j] = reflect101(2 * x - 2 + j, pc.sw);
    float acc = 0.0;
    for (int i = 0; i < 5; ++i) {
        uint row = sbase + uint(reflect101(2 * y - 2 + i, pc.sh) * pc.sw);
        float h = 0.0;
        for (int j = 0; j < 5; ++j) h += K5[j] * pc.src.v[row + uint(cols[j])];
        acc += K5[i] * h;
    }
    pc.dst.v[z * uint(pc.dw * pc.dh) + uint(y * pc.dw + x)] = acc * (1.0 / 256.0);
}

#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// cv::pyrDown on every plane: 5x5 binomial [1 4 6 4 1]/16 per axis around
// source sample 2x (reflect-101 borders), output ((w+1)/2, (h+1)/2).
layout(local_size_x = VKFUSE_LINE_GROUP) in;
#define BUFFERS(X) X(0, plane_t, src) X(1, plane_t, dst)
#include "bindings.glsl"
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int sw;
    int sh;
    int dw;
    int dh;
} pc;

const float K5[5] = float[5](1.0, 4.0, 6.0, 4.0, 1.0);
// Output rows per invocation: consecutive outputs share three of their five
// source rows, so the invocation keeps the rows' horizontal sums and loads two
// new source rows per output instead of five.
const int ROWS = VKFUSE_PYR_DOWN_ROWS;

float row_sum(uint sbase, int r, int cols[5]) {
    uint row = sbase + uint(reflect101(r, pc.sh) * pc.sw);
    float h = 0.0;
    for (int j = 0; j < 5; ++j) h += K5[j] * BUF(src).v[row + uint(cols[j])];
    return h;
}

void main() {
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), uint(pc.dw));
    int x = item.x, y0 = item.y * ROWS;
    uint z = gl_WorkGroupID.z;
    if (x >= pc.dw || y0 >= pc.dh) return;
    uint sbase = z * uint(pc.sw * pc.sh);
    int cols[5];
    for (int j = 0; j < 5; ++j) cols[j] = reflect101(2 * x - 2 + j, pc.sw);
    float h[5];  // horizontal sums of source rows 2y - 2 .. 2y + 2
    for (int i = 0; i < 5; ++i) h[i] = row_sum(sbase, 2 * y0 - 2 + i, cols);
    for (int r = 0; r < ROWS; ++r) {
        int y = y0 + r;
        if (y >= pc.dh) break;
        if (r > 0) {
            h[0] = h[2];
            h[1] = h[3];
            h[2] = h[4];
            h[3] = row_sum(sbase, 2 * y + 1, cols);
            h[4] = row_sum(sbase, 2 * y + 2, cols);
        }
        float acc = 0.0;
        for (int i = 0; i < 5; ++i) acc += K5[i] * h[i];
        BUF(dst).v[z * uint(pc.dw * pc.dh) + uint(y * pc.dw + x)] = TO_PLANE(acc * (1.0 / 256.0));
    }
}

#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// pyr_down.comp four output columns at a time, for source widths that are a
// multiple of 8: outputs x .. x+3 of a source row read its samples
// 2x-4 .. 2x+11 as four plane4, each output's horizontal sum added in
// pyr_down's order. At the row's ends the quads outside it are loaded from
// inside and the two samples reflect-101 needs are selected, without a
// branch: on a SIMD device a border lane's branch would make its neighbours
// run the sample-by-sample path too.
#define BUFFERS(X) X(0, plane4_t, src4) X(1, plane4_t, dst4)
#include "bindings.glsl"
layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int sw;
    int sh;
    int dw;
    int dh;
} pc;

const int ROWS = VKFUSE_PYR_DOWN_ROWS;  // output rows per invocation, as pyr_down.comp

float tap(float a, float b, float c, float d, float e) {
    return (((1.0 * a + 4.0 * b) + 6.0 * c) + 4.0 * d) + 1.0 * e;
}

// Horizontal sums of source row r for outputs x .. x+3.
vec4 row_sums(uint sbase, int r, int x) {
    uint row = sbase + uint(reflect101(r, pc.sh) * pc.sw);
    uint q = (row + uint(2 * x)) / 4u;  // the quad of sample 2x
    // x + 3 is the row's last output when sample 2x + 8 is one past its last
    // (sw and 2x are multiples of 8, and 2x <= sw - 8).
    bool first = x == 0, last = 2 * x + 8 >= pc.sw;
    vec4 v0 = vec4(BUF(src4).v[first ? q : q - 1u]);
    vec4 v1 = vec4(BUF(src4).v[q]);
    vec4 v2 = vec4(BUF(src4).v[q + 1u]);
    vec4 v3 = vec4(BUF(src4).v[last ? q + 1u : q + 2u]);
    v0.zw = mix(v0.zw, v1.zy, bvec2(first));  // samples -2, -1 are 2, 1
    v3.x = mix(v3.x, v2.z, last);             // sample sw is sw - 2
    // output x + t reads samples 2(x+t)-2 .. 2(x+t)+2: window entries 2+2t .. 6+2t
    return vec4(tap(v0.z, v0.w, v1.x, v1.y, v1.z), tap(v1.x, v1.y, v1.z, v1.w, v2.x),
                tap(v1.z, v1.w, v2.x, v2.y, v2.z), tap(v2.x, v2.y, v2.z, v2.w, v3.x));
}

void main() {
    int x = int(gl_GlobalInvocationID.x) * 4, y0 = int(gl_GlobalInvocationID.y) * ROWS;
    uint z = gl_WorkGroupID.z;
    if (x >= pc.dw || y0 >= pc.dh) return;
    uint sbase = z * uint(pc.sw * pc.sh);
    vec4 h[5];  // horizontal sums of source rows 2y - 2 .. 2y + 2
    for (int i = 0; i < 5; ++i) h[i] = row_sums(sbase, 2 * y0 - 2 + i, x);
    for (int r = 0; r < ROWS; ++r) {
        int y = y0 + r;
        if (y >= pc.dh) break;
        if (r > 0) {
            h[0] = h[2];
            h[1] = h[3];
            h[2] = h[4];
            h[3] = row_sums(sbase, 2 * y + 1, x);
            h[4] = row_sums(sbase, 2 * y + 2, x);
        }
        vec4 acc = (((1.0 * h[0] + 4.0 * h[1]) + 6.0 * h[2]) + 4.0 * h[3]) + 1.0 * h[4];
        BUF(dst4).v[(z * uint(pc.dw * pc.dh) + uint(y * pc.dw + x)) / 4u] = TO_PLANE4(acc * (1.0 / 256.0));
    }
}

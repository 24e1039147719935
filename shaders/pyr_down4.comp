#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// pyr_down.comp 4 QUADS output columns at a time, for source widths that are
// a multiple of 8 QUADS: outputs x .. x + 4 QUADS - 1 of a source row read its
// samples 2x-4 .. 2x + 8 QUADS + 3 as 2 QUADS + 2 plane4 (neighbouring
// outputs share them: the more quads, the fewer loads per output), each
// output's horizontal sum added in pyr_down's order. At the row's ends the
// quads outside it are loaded from inside and the two samples reflect-101
// needs are selected, without a branch: on a SIMD device a border lane's
// branch would make its neighbours run the sample-by-sample path too.
#define BUFFERS(X) X(0, plane4_t, src4) X(1, plane4_t, dst4)
#include "bindings.glsl"
layout(local_size_x = VKFUSE_LINE_GROUP) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int sw;
    int sh;
    int dw;
    int dh;
} pc;

const int ROWS = VKFUSE_PYR_DOWN_ROWS;  // output rows per invocation, as pyr_down.comp
// Output quads per row and invocation, 1 or 2 (arrays below are sized for 2:
// a specialization constant does not size them).
layout(constant_id = 0) const int QUADS = 1;
const int WINDOW = 2 * QUADS + 2;  // source quads per row and invocation

float tap(float a, float b, float c, float d, float e) {
    return (((1.0 * a + 4.0 * b) + 6.0 * c) + 4.0 * d) + 1.0 * e;
}

// Horizontal sums of source row r for outputs x .. x + 4 QUADS - 1.
void row_sums(uint sbase, int r, int x, out vec4 sums[2]) {
    uint row = sbase + uint(reflect101(r, pc.sh) * pc.sw);
    uint q = (row + uint(2 * x)) / 4u;  // the quad of sample 2x: window quad 1
    // The invocation's last output is the row's when sample 2x + 8 QUADS is one
    // past its last (sw and 2x are multiples of 8 QUADS, 2x <= sw - 8 QUADS).
    bool first = x == 0, last = 2 * x + 8 * QUADS >= pc.sw;
    vec4 v[6];
    v[0] = vec4(BUF(src4).v[first ? q : q - 1u]);
    for (int i = 1; i < WINDOW - 1; ++i) v[i] = vec4(BUF(src4).v[q + uint(i - 1)]);
    v[WINDOW - 1] = vec4(BUF(src4).v[last ? q + uint(WINDOW - 3) : q + uint(WINDOW - 2)]);
    v[0].zw = mix(v[0].zw, v[1].zy, bvec2(first));                      // samples -2, -1 are 2, 1
    v[WINDOW - 1].x = mix(v[WINDOW - 1].x, v[WINDOW - 2].z, last);      // sample sw is sw - 2
    // Output x + 4o + t reads samples 2(x+4o+t)-2 .. 2(x+4o+t)+2: window
    // entries 8o + 2 + 2t .. 8o + 6 + 2t, in quads 2o .. 2o + 3.
    for (int o = 0; o < QUADS; ++o) {
        vec4 a = v[2 * o], b = v[2 * o + 1], c = v[2 * o + 2], d = v[2 * o + 3];
        sums[o] = vec4(tap(a.z, a.w, b.x, b.y, b.z), tap(b.x, b.y, b.z, b.w, c.x), tap(b.z, b.w, c.x, c.y, c.z),
                       tap(c.x, c.y, c.z, c.w, d.x));
    }
}

void main() {
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), uint(pc.dw / (4 * QUADS)));  // dw: whole groups of QUADS
    int x = item.x * 4 * QUADS, y0 = item.y * ROWS;
    uint z = gl_WorkGroupID.z;
    if (x >= pc.dw || y0 >= pc.dh) return;
    uint sbase = z * uint(pc.sw * pc.sh);
    vec4 h[5][2];  // horizontal sums of source rows 2y - 2 .. 2y + 2
    for (int i = 0; i < 5; ++i) row_sums(sbase, 2 * y0 - 2 + i, x, h[i]);
    for (int r = 0; r < ROWS; ++r) {
        int y = y0 + r;
        if (y >= pc.dh) break;
        if (r > 0) {
            h[0] = h[2];
            h[1] = h[3];
            h[2] = h[4];
            row_sums(sbase, 2 * y + 1, x, h[3]);
            row_sums(sbase, 2 * y + 2, x, h[4]);
        }
        uint out4 = (z * uint(pc.dw * pc.dh) + uint(y * pc.dw + x)) / 4u;
        for (int o = 0; o < QUADS; ++o) {
            vec4 acc = (((1.0 * h[0][o] + 4.0 * h[1][o]) + 6.0 * h[2][o]) + 4.0 * h[3][o]) + 1.0 * h[4][o];
            BUF(dst4).v[out4 + uint(o)] = TO_PLANE4(acc * (1.0 / 256.0));
        }
    }
}

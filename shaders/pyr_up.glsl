// The one-output-pair pyrUp gather of lap_fuse.comp and lap_collapse.comp
// (pyr_up4.glsl is its four-lane twin). The including kernel binds the source
// planes as `coarse` (plane_t).
// cv::pyrUp at the 2 x 2 outputs (2i + a, 2j + b), a, b in {0, 1} (as
// out[a][b]), from the 3 x 3 source samples they all draw on: 9 loads for 4
// outputs. Per axis an even output weighs source samples (i - 1, i, i + 1) by
// (1, 6, 1)/8, an odd one (i, i + 1) by (4, 4)/8; the left/top border
// reflects (reflect-101), the right/bottom one repeats the last sample, a
// length-1 axis repeats its only sample (8/8): OpenCV's own edge handling.
// Horizontal sums per source row first, then the vertical combination, as
// OpenCV adds them.
float pyr_up_h(vec3 v, int parity, int n) {
    if (n == 1) return 8.0 * v.y;
    return parity == 0 ? (1.0 * v.x + 6.0 * v.y) + 1.0 * v.z : 4.0 * v.y + 4.0 * v.z;
}

mat2 pyr_up_block(uint base, int sw, int sh, int i, int j) {
    // Source rows / columns: even outputs read (i - 1 reflected, i, i + 1
    // clamped), odd outputs (i, i + 1 clamped): the three cover both.
    ivec3 r = ivec3(i == 0 ? min(1, sh - 1) : i - 1, i, min(i + 1, sh - 1));
    ivec3 c = ivec3(j == 0 ? min(1, sw - 1) : j - 1, j, min(j + 1, sw - 1));
    vec3 h_even, h_odd;  // horizontal sums per source row for even / odd output columns
    for (int a = 0; a < 3; ++a) {
        uint row = base + uint(r[a] * sw);
        vec3 v = vec3(float(BUF(coarse).v[row + uint(c.x)]), float(BUF(coarse).v[row + uint(c.y)]),
                      float(BUF(coarse).v[row + uint(c.z)]));
        h_even[a] = pyr_up_h(v, 0, sw);
        h_odd[a] = pyr_up_h(v, 1, sw);
    }
    mat2 out_;
    out_[0][0] = pyr_up_h(h_even, 0, sh) * (1.0 / 64.0);
    out_[0][1] = pyr_up_h(h_odd, 0, sh) * (1.0 / 64.0);
    out_[1][0] = pyr_up_h(h_even, 1, sh) * (1.0 / 64.0);
    out_[1][1] = pyr_up_h(h_odd, 1, sh) * (1.0 / 64.0);
    return out_;
}


// Whole-sample symmetric lifting on one line held in split layout (even
// positions, the approximation, at [0, half_len); odd positions, the detail,
// at [half_len, n)). Positions are the line's natural ones, so the steps read
// exactly as core/wavelet.hpp states them:
//   x[q] += c0 x[R(q + o0, n)] + c1 x[R(q + o1, n)] for every q of one parity,
// R = reflect101, which keeps parity, so a step never reads what it writes.
// The scheme buffer (pc.scheme) holds
//   [steps, Ke, Ko, 1/Ke high, 1/Ke low, 1/Ko high, 1/Ko low,
//    then per step: parity, taps, c0, c1, o0, o1].

// Where a line's coefficients live: buffer plus strides.
struct LineView {
    uint plane_stride;
    int line_stride;
    int elem_stride;
};

uint lift_slot(LineView v, uint plane, int line, int pos) {
    int i = (pos & 1) == 0 ? pos >> 1 : pc.half_len + (pos >> 1);
    return plane * v.plane_stride + uint(line * v.line_stride + i * v.elem_stride);
}

// sign = +1 applies step s, -1 undoes it.
void lift_step(LineView v, uint plane, int line, int n, int s, float sign) {
    uint base = 7u + uint(s) * 6u;
    int parity = int(BUF(scheme).v[base]);
    int taps = int(BUF(scheme).v[base + 1u]);
    float c0 = BUF(scheme).v[base + 2u], c1 = BUF(scheme).v[base + 3u];
    int o0 = int(BUF(scheme).v[base + 4u]), o1 = int(BUF(scheme).v[base + 5u]);
    for (int q = parity; q < n; q += 2) {
        // x + sign * (c0 a + c1 b) as one sum rounded once (compensated.glsl):
        // a plain-float step rounds three times, and symmetric bior4.4's eight
        // steps per level made a fed-back image drift past the stress suite's
        // bound (tests/stress/test_stress_feedback).
        uint at = lift_slot(v, plane, line, q);
        Dot2 d = dot2_of(float(BUF(LIFT_COEF).v[at]));
        dot2_add(d, sign * c0, BUF(LIFT_COEF).v[lift_slot(v, plane, line, reflect101(q + o0, n))]);
        if (taps > 1) dot2_add(d, sign * c1, BUF(LIFT_COEF).v[lift_slot(v, plane, line, reflect101(q + o1, n))]);
        BUF(LIFT_COEF).v[at] = TO_PLANE(dot2_result(d));
    }
}

// Multiplies (forward) or divides (inverse) even positions by Ke, odd by Ko.
// The division is x (1/K)_high + x (1/K)_low as one sum rounded once
// (compensated.glsl): a GPU's x / K may be 2.5 ulps off (SPIR-V allows it for
// OpFDiv), and a rig re-fusing its output would drift by as much per level.
void lift_scale(LineView v, uint plane, int line, int n, bool forward) {
    for (int p = 0; p < n; ++p) {
        uint at = lift_slot(v, plane, line, p);
        uint odd = uint(p & 1);
        float x = BUF(LIFT_COEF).v[at];
        if (forward) {
            BUF(LIFT_COEF).v[at] = TO_PLANE(x * BUF(scheme).v[1u + odd]);
        } else {
            Dot2 d = dot2_of(0.0);
            dot2_add(d, x, BUF(scheme).v[3u + 2u * odd]);
            dot2_add(d, x, BUF(scheme).v[4u + 2u * odd]);
            BUF(LIFT_COEF).v[at] = TO_PLANE(dot2_result(d));
        }
    }
}

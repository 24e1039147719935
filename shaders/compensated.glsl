// Filter outputs as dot products rounded once. A filter output is a sum of
// taps x samples; the kernels that compute them (the wavelet transforms and
// lifting steps) accumulate it with more than float's precision and round the
// result to float once, so that a rig re-fusing its own output (the stress
// suite's feedback passes) meets only that one rounding per output and pass.
// dot2_of(x) starts a sum at x (dot2_of(0.0): an empty one).
// A kernel including this file is built in two arithmetics (CMakeLists.txt),
// the recorder picks one per device (ContextOptions::filter_arithmetic):
//
//  - VKFUSE_FLOAT64_FILTERS: a double accumulator, one fma per tap. Where
//    doubles are native vector lanes (a CPU device such as lavapipe) this is
//    the cheapest way to the precision.
//  - otherwise Ogita, Rump and Oishi's Dot2 in float: each product's rounding
//    error (through fma) and each addition's (Knuth's TwoSum) go into a second
//    accumulator, about twice float's precision in about ten float operations
//    per tap, for devices whose double rate is a fraction of their float rate.
//    `precise` keeps the compiler from reassociating the error terms away;
//    where fma is not fused, the product error reads 0 and only the additions
//    are compensated.
//
// Either keeps one pass within a few ulps of the double reference and a fed-
// back image's drift near one rounding (tests/test_vk_precision.cpp measures
// both); float64 is the closer of the two, and their outputs may differ in
// the last bits.
#ifdef VKFUSE_FLOAT64_FILTERS

struct Dot2 {
    double sum;
};

Dot2 dot2_of(float x) { return Dot2(double(x)); }

void dot2_add(inout Dot2 d, float a, float b) {
    d.sum = fma(double(a), double(b), d.sum);
}

float dot2_result(Dot2 d) { return float(d.sum); }

#else

struct Dot2 {
    float sum;
    float err;
};

Dot2 dot2_of(float x) { return Dot2(x, 0.0); }

void dot2_add(inout Dot2 d, float a, float b) {
    precise float p = a * b;
    precise float product_err = fma(a, b, -p);
    precise float t = d.sum + p;
    precise float z = t - d.sum;
    precise float sum_err = (d.sum - (t - z)) + (p - z);
    d.sum = t;
    d.err += product_err + sum_err;
}

float dot2_result(Dot2 d) {
    precise float r = d.sum + d.err;
    return r;
}

#endif

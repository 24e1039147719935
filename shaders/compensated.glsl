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
//    `precise` keeps the compiler from reassociating the error terms away.
//    Vulkan promises fma only the precision of a multiply and an add; where
//    the context found it not fused (vk/probes/fma_probe.cpp, SPLIT_PRODUCTS) each
//    product's error comes from Dekker's split instead: exact for any float
//    product that neither overflows nor underflows, at about 17 operations.
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

// Set by the context for every pipeline (kSplitProductsConstant in
// context_impl.hpp): true where fma is not fused.
layout(constant_id = 100) const bool SPLIT_PRODUCTS = false;

Dot2 dot2_of(float x) { return Dot2(x, 0.0); }

// a's high half (its leading 12 bits) by Veltkamp's split: a = hi + lo exactly.
float split_high(float a) {
    precise float c = 4097.0 * a;  // 2^12 + 1
    precise float hi = c - (c - a);
    return hi;
}

// a * b - fl(a * b), exactly, without fma (Dekker's TwoProduct).
float product_error(float a, float b, float p) {
    if (!SPLIT_PRODUCTS) {
        precise float e = fma(a, b, -p);
        return e;
    }
    precise float ah = split_high(a);
    precise float al = a - ah;
    precise float bh = split_high(b);
    precise float bl = b - bh;
    precise float e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return e;
}

void dot2_add(inout Dot2 d, float a, float b) {
    precise float p = a * b;
    precise float product_err = product_error(a, b, p);
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

// The per-pixel fusions (Brovey, channel-sum, the mean) from the frames as
// uploaded, shared by pointwise_fuse.comp and by metrics.comp, which fuses
// its pixels itself where a plan fuses pointwise (no fused planes stored or
// read). Both run the same code per pixel, so both give the same bits.
// A kernel includes frames.glsl with VKFUSE_READS_FRAMES first, declares a
// `float thresholds` buffer and a push field `scaled_threshold`.

// The method and K are specialization constants, so that each pipeline holds
// one method's code with its loops over the frames unrolled: lavapipe runs
// both sides of every branch it cannot skip, and keeps unrolled values in
// registers rather than reading them again. metrics.comp's default,
// VKFUSE_POINTWISE_NONE, reads fused planes and fuses nothing.
layout(constant_id = 0) const uint METHOD = VKFUSE_POINTWISE_DEFAULT;  // VKFUSE_POINTWISE_* (kernel_codes.h)
layout(constant_id = 1) const uint FRAMES = 1u;                        // K

// docs/spec.md's s >= 1e-6, with the threshold the smallest float >= 1e-6
// (0x358637BE; the literal 1e-6 rounds below it, to 9.99999997e-7, which
// would take the ratio for a sum that is below 1e-6). Float32 frames reach the
// device scaled by a power of two per sensor (vk/engine/magnitude.hpp), and so does
// this threshold, written by the host every run; 8-bit frames never are.
float brovey_threshold(uint s) {
    if (METHOD != VKFUSE_POINTWISE_BROVEY) return 0.0;
    return pc.scaled_threshold != 0u ? BUF(thresholds).v[s] : uintBitsToFloat(0x358637BEu);
}

// The fused values of one channel from its K values v_k, as vec4 (a quad's
// four pixels, one pixel's channels in .xyz, or one sample in .x). Brovey
// takes two rounds over the frames: s = sum_k max(v_k, 0) first, then
// sum_k (max(v_k, 0) / s) v_k, each term divided before it is multiplied so
// that no product of two small values underflows (float32 frames keep their
// own magnitude, vk/engine/magnitude.hpp).
struct Fuser {
    vec4 a, b;  // mean: Kahan sum and compensation; brovey: s, then the weighted sum
    vec4 mean_sum;
};

void fuser_add(inout Fuser f, vec4 v) {
    if (METHOD == VKFUSE_POINTWISE_MEAN) {  // Kahan-compensated: a plain float sum of 100 frames drifts by ~1e-5
        precise vec4 y = v - f.b;
        precise vec4 t = f.a + y;
        f.b = (t - f.a) - y;
        f.a = t;
    } else {
        f.a += max(v, 0.0);
        f.mean_sum += v;
    }
}

void fuser_weigh(inout Fuser f, vec4 v) { f.b += (max(v, 0.0) / f.a) * v; }

vec4 fuser_result(Fuser f, float threshold) {
    if (METHOD == VKFUSE_POINTWISE_MEAN) return f.a / float(FRAMES);
    return mix(f.mean_sum / float(FRAMES), f.b, greaterThanEqual(f.a, vec4(threshold)));
}

// Sensor s's fused pixels 4i .. 4i+3 (planes of whole quads).
Quad fuse_quad(uint s, uint i, float threshold) {
    uint K = FRAMES;
    if (METHOD == VKFUSE_POINTWISE_CHANNEL_SUM)
        return Quad(frame_channel_quad(s * K, i, 0u), frame_channel_quad(s * K + 1u, i, 1u),
                    frame_channel_quad(s * K + 2u, i, 2u));
    Fuser f0 = Fuser(vec4(0.0), vec4(0.0), vec4(0.0)), f1 = f0, f2 = f0;
    if (METHOD == VKFUSE_POINTWISE_BROVEY) {
        // Both rounds from the frames read once: unrolled (K up to lavapipe's
        // 32), the quads stay in registers.
        Quad q[FRAMES];
        for (uint k = 0u; k < K; ++k) {
            q[k] = frame_quad(s * K + k, i);
            fuser_add(f0, q[k].c0);
            fuser_add(f1, q[k].c1);
            fuser_add(f2, q[k].c2);
        }
        for (uint k = 0u; k < K; ++k) {
            fuser_weigh(f0, q[k].c0);
            fuser_weigh(f1, q[k].c1);
            fuser_weigh(f2, q[k].c2);
        }
    } else {
        for (uint k = 0u; k < K; ++k) {
            Quad q = frame_quad(s * K + k, i);
            fuser_add(f0, q.c0);
            fuser_add(f1, q.c1);
            fuser_add(f2, q.c2);
        }
    }
    return Quad(fuser_result(f0, threshold), fuser_result(f1, threshold), fuser_result(f2, threshold));
}

// Sensor s's fused pixel 4i + 3 (last) or 4i, its channels in .xyz (C = 1:
// in .x), each channel's arithmetic that of fuse_quad's lanes.
vec4 fuse_pixel(uint s, uint i, bool last, float threshold) {
    uint K = FRAMES;
    if (METHOD == VKFUSE_POINTWISE_CHANNEL_SUM)
        return vec4(frame_pixel(s * K, i, last).x, frame_pixel(s * K + 1u, i, last).y,
                    frame_pixel(s * K + 2u, i, last).z, 0.0);
    Fuser f = Fuser(vec4(0.0), vec4(0.0), vec4(0.0));
    vec4 v[FRAMES];
    for (uint k = 0u; k < K; ++k) {
        v[k] = frame_pixel(s * K + k, i, last);
        fuser_add(f, v[k]);
    }
    if (METHOD == VKFUSE_POINTWISE_BROVEY)
        for (uint k = 0u; k < K; ++k) fuser_weigh(f, v[k]);
    return fuser_result(f, threshold);
}

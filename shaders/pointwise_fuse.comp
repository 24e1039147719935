#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Methods that fuse each pixel on its own: Brovey, channel-sum and the mean
// (the background model averages up to a few hundred frames), in one pass from
// the frames as uploaded to the fused planes (for the metrics) and the fused
// image as read back: no unpack and no pack pass. Workgroup z is the sensor.
// Where a plane holds a multiple of 4 pixels each invocation fuses 4 pixels
// (frames.glsl's quads); otherwise one, with the same arithmetic per pixel.
// Nothing is stored between reading and fusing, so under fp16 storage only the
// planes the metrics read are float16; the image read back is float32.
#define BUFFERS(X) X(0, uint, frame_words) X(1, vec4, frame_quads) X(2, plane_t, dst) X(3, plane4_t, dst4) \
    X(4, float, image) X(5, vec4, image_quads) X(6, float, thresholds)
#include "bindings.glsl"
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint pixels;
    uint channels;
    uint is_u8;
    uint scaled_threshold;  // brovey: sensor s compares with thresholds.v[s]
    uint quads;   // pixels % 4 == 0
    uint write_planes;  // the metrics read them
    uint write_image;   // the host reads it
} pc;
#define VKFUSE_READS_FRAMES
#define VKFUSE_WRITES_IMAGES
#include "frames.glsl"

// The method and K are specialization constants, so that each pipeline holds
// one method's code with its loops over the frames unrolled: lavapipe runs
// both sides of every branch it cannot skip, and keeps unrolled values in
// registers rather than reading them again.
layout(constant_id = 0) const uint METHOD = VKFUSE_POINTWISE_MEAN;  // VKFUSE_POINTWISE_* (kernel_codes.h)
layout(constant_id = 1) const uint FRAMES = 1u;                     // K

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
// four pixels, or one pixel in .x). Brovey takes two rounds over the frames:
// s = sum_k max(v_k, 0) first, then sum_k (max(v_k, 0) / s) v_k, each term
// divided before it is multiplied so that no product of two small values
// underflows (float32 frames keep their own magnitude, vk/engine/magnitude.hpp).
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

// Channel c of sensor s's fused pixel p.
float fuse_sample(uint s, uint p, uint c, float threshold) {
    uint K = FRAMES;
    if (METHOD == VKFUSE_POINTWISE_CHANNEL_SUM) return frame_sample(s * K + c, p, c);  // channel c lit by LED c alone
    Fuser f = Fuser(vec4(0.0), vec4(0.0), vec4(0.0));
    for (uint k = 0u; k < K; ++k) fuser_add(f, vec4(frame_sample(s * K + k, p, c), 0.0, 0.0, 0.0));
    if (METHOD == VKFUSE_POINTWISE_BROVEY)
        for (uint k = 0u; k < K; ++k) fuser_weigh(f, vec4(frame_sample(s * K + k, p, c), 0.0, 0.0, 0.0));
    return fuser_result(f, threshold).x;
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

void main() {
    uint i = linear_index(256u), s = gl_WorkGroupID.z, C = pc.channels;
    if (i >= (pc.quads != 0u ? pc.pixels / 4u : pc.pixels)) return;
    float threshold = brovey_threshold(s);
    if (pc.quads == 0u) {
        for (uint c = 0u; c < C; ++c) {
            float v = fuse_sample(s, i, c, threshold);
            if (pc.write_planes != 0u) BUF(dst).v[(s * C + c) * pc.pixels + i] = TO_PLANE(v);
            if (pc.write_image != 0u) store_image_sample(s, i, c, v);
        }
        return;
    }
    Quad out_ = fuse_quad(s, i, threshold);
    if (pc.write_planes != 0u) {
        uint o = (s * C * pc.pixels) / 4u + i, stride = pc.pixels / 4u;
        BUF(dst4).v[o] = TO_PLANE4(out_.c0);
        if (C == 3u) {
            BUF(dst4).v[o + stride] = TO_PLANE4(out_.c1);
            BUF(dst4).v[o + 2u * stride] = TO_PLANE4(out_.c2);
        }
    }
    if (pc.write_image != 0u) store_image_quad(s, i, out_);
}

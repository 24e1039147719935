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
    uint frames;
    uint method;  // VKFUSE_POINTWISE_* (kernel_codes.h)
    uint scaled_threshold;  // brovey: sensor s compares with thresholds.v[s]
    uint quads;   // pixels % 4 == 0
    uint write_planes;  // the metrics read them
    uint write_image;   // the host reads it
} pc;
#define VKFUSE_READS_FRAMES
#define VKFUSE_WRITES_IMAGES
#include "frames.glsl"

// docs/spec.md's s >= 1e-6, with the threshold the smallest float >= 1e-6
// (0x358637BE; the literal 1e-6 rounds below it, to 9.99999997e-7, which
// would take the ratio for a sum that is below 1e-6). Float32 frames reach the
// device scaled by a power of two per sensor (vk/engine/magnitude.hpp), and so does
// this threshold, written by the host every run; 8-bit frames never are.
float brovey_threshold(uint s) {
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
    if (pc.method == VKFUSE_POINTWISE_MEAN) {  // Kahan-compensated: a plain float sum of 100 frames drifts by ~1e-5
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
    if (pc.method == VKFUSE_POINTWISE_MEAN) return f.a / float(pc.frames);
    return mix(f.mean_sum / float(pc.frames), f.b, greaterThanEqual(f.a, vec4(threshold)));
}

void main() {
    uint i = linear_index(256u), s = gl_WorkGroupID.z, C = pc.channels, K = pc.frames;
    if (i >= (pc.quads != 0u ? pc.pixels / 4u : pc.pixels)) return;
    float threshold = pc.method == VKFUSE_POINTWISE_BROVEY ? brovey_threshold(s) : 0.0;
    if (pc.quads == 0u) {
        for (uint c = 0u; c < C; ++c) {
            float v;
            if (pc.method == VKFUSE_POINTWISE_CHANNEL_SUM) {  // channel c comes from frame c (lit by LED c alone)
                v = frame_sample(s * K + c, i, c);
            } else {
                Fuser f = Fuser(vec4(0.0), vec4(0.0), vec4(0.0));
                for (uint k = 0u; k < K; ++k) fuser_add(f, vec4(frame_sample(s * K + k, i, c), 0.0, 0.0, 0.0));
                if (pc.method == VKFUSE_POINTWISE_BROVEY)
                    for (uint k = 0u; k < K; ++k) fuser_weigh(f, vec4(frame_sample(s * K + k, i, c), 0.0, 0.0, 0.0));
                v = fuser_result(f, threshold).x;
            }
            if (pc.write_planes != 0u) BUF(dst).v[(s * C + c) * pc.pixels + i] = TO_PLANE(v);
            if (pc.write_image != 0u) store_image_sample(s, i, c, v);
        }
        return;
    }
    Quad out_;
    if (pc.method == VKFUSE_POINTWISE_CHANNEL_SUM) {
        out_ = Quad(frame_quad(s * K, i).c0, frame_quad(s * K + 1u, i).c1, frame_quad(s * K + 2u, i).c2);
    } else {
        Fuser f0 = Fuser(vec4(0.0), vec4(0.0), vec4(0.0)), f1 = f0, f2 = f0;
        for (uint k = 0u; k < K; ++k) {
            Quad q = frame_quad(s * K + k, i);
            fuser_add(f0, q.c0);
            fuser_add(f1, q.c1);
            fuser_add(f2, q.c2);
        }
        if (pc.method == VKFUSE_POINTWISE_BROVEY)
            for (uint k = 0u; k < K; ++k) {
                Quad q = frame_quad(s * K + k, i);
                fuser_weigh(f0, q.c0);
                fuser_weigh(f1, q.c1);
                fuser_weigh(f2, q.c2);
            }
        out_ = Quad(fuser_result(f0, threshold), fuser_result(f1, threshold), fuser_result(f2, threshold));
    }
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

#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Methods that fuse each pixel on its own: Brovey, channel-sum and the mean
// (the background model averages up to a few hundred frames), in one pass from
// the frames as uploaded to the fused planes (for the metrics) and the fused
// image as read back: no unpack and no pack pass. Workgroup z is the sensor.
// Where rows are whole quads and a plan asks for metrics, metrics.comp fuses
// its pixels itself with the same per-pixel code (pointwise.glsl) and this
// kernel is not recorded.
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

#define VKFUSE_POINTWISE_DEFAULT VKFUSE_POINTWISE_MEAN
#include "pointwise.glsl"

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

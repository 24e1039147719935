// The host-facing ends of a cycle: frames as uploaded (HWC, 8-bit or float32)
// and fused images as read back (HWC float32). A kernel that reads frames
// defines VKFUSE_READS_FRAMES, declares the upload buffer twice in BUFFERS, as
// `uint frame_words` and `vec4 frame_quads`, and has push fields `pixels`,
// `channels` and `is_u8`; one that writes images defines VKFUSE_WRITES_IMAGES
// and declares `float image` and `vec4 image_quads`.
// Channels are 1 or 3. "Quad" functions serve planes of whole quads
// (pixels % 4 == 0): pixels 4i .. 4i+3, one vec4 per channel; for C = 3 the
// interleaved words hold r0 g0 b0 r1 | g1 b1 r2 g2 | b2 r3 g3 b3.
struct Quad {
    vec4 c0, c1, c2;  // channels 0, 1, 2 of four pixels (C = 1: c0 only)
};

#ifdef VKFUSE_READS_FRAMES
// The four bytes of a word, low first, each / 255 as frame_sample divides.
vec4 bytes_of(uint word) {
    return vec4((uvec4(word) >> uvec4(0u, 8u, 16u, 24u)) & 255u) / 255.0;
}

// Frame f's pixels 4i .. 4i+3 (frame f: sensor s = f / K, frame k = f % K).
Quad frame_quad(uint f, uint i) {
    uint C = pc.channels;
    uint first = f * pc.pixels * C / 4u + i * C;  // in words, or in vec4 of float input
    vec4 q0, q1, q2;
    if (pc.is_u8 != 0u) {
        q0 = bytes_of(BUF(frame_words).v[first]);
        if (C == 1u) return Quad(q0, q0, q0);
        q1 = bytes_of(BUF(frame_words).v[first + 1u]);
        q2 = bytes_of(BUF(frame_words).v[first + 2u]);
    } else {
        q0 = BUF(frame_quads).v[first];
        if (C == 1u) return Quad(q0, q0, q0);
        q1 = BUF(frame_quads).v[first + 1u];
        q2 = BUF(frame_quads).v[first + 2u];
    }
    return Quad(vec4(q0.x, q0.w, q1.z, q2.y), vec4(q0.y, q1.x, q1.w, q2.z), vec4(q0.z, q1.y, q2.x, q2.w));
}

// Channel c of frame f's pixels 4i .. 4i+3 (C = 3): of float32 frames only
// that channel's four samples are read, not the quad's twelve.
vec4 frame_channel_quad(uint f, uint i, uint c) {
    if (pc.is_u8 != 0u) {
        Quad q = frame_quad(f, i);
        return c == 0u ? q.c0 : c == 1u ? q.c1 : q.c2;
    }
    uint first = (f * pc.pixels + 4u * i) * 3u + c;
    return uintBitsToFloat(uvec4(BUF(frame_words).v[first], BUF(frame_words).v[first + 3u],
                                 BUF(frame_words).v[first + 6u], BUF(frame_words).v[first + 9u]));
}

// Channel c of pixel p of frame f.
float frame_sample(uint f, uint p, uint c) {
    uint idx = (f * pc.pixels + p) * pc.channels + c;
    if (pc.is_u8 == 0u) return uintBitsToFloat(BUF(frame_words).v[idx]);
    return float((BUF(frame_words).v[idx >> 2u] >> ((idx & 3u) * 8u)) & 255u) / 255.0;
}

#endif

#ifdef VKFUSE_WRITES_IMAGES
// Sensor s's fused pixels 4i .. 4i+3 into its read-back image.
void store_image_quad(uint s, uint i, Quad q) {
    uint first = (s * pc.pixels / 4u + i) * pc.channels;  // vec4 index of pixel 4i's first sample
    if (pc.channels == 1u) {
        BUF(image_quads).v[first] = q.c0;
        return;
    }
    BUF(image_quads).v[first] = vec4(q.c0.x, q.c1.x, q.c2.x, q.c0.y);
    BUF(image_quads).v[first + 1u] = vec4(q.c1.y, q.c2.y, q.c0.z, q.c1.z);
    BUF(image_quads).v[first + 2u] = vec4(q.c2.z, q.c0.w, q.c1.w, q.c2.w);
}

void store_image_sample(uint s, uint p, uint c, float v) {
    BUF(image).v[(s * pc.pixels + p) * pc.channels + c] = v;
}
#endif

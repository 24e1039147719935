#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Change detection (docs/spec.md, "Skipping"; core/skip.cpp is its CPU twin):
// one workgroup per 32 x 32 tile (x, y) of sensor z, one invocation per row of
// the tile. Each takes, over the K frames of the cycle and every channel, the
// largest |frame - background mean| times the tile's inverse noise under that
// frame's setting; the tile's score is the largest of its rows, taken with
// atomicMax on its bits in the zeroed score buffer (scores are never
// negative, and non-negative floats order as their bits do: on lavapipe that
// costs less than a reduction through shared memory, whose barriers dominate
// a kernel this light). Frames are 8-bit, as uploaded (HWC, 4 samples a
// word); the means are 16-bit fixed point in the same order (an 8-bit level
// times 256, 2 samples a word), so a row is read as whole words and compared
// in integers: 8 C words of frame and 16 C of means for its 32 C samples.
// With `previous` set (SkipPolicy::Static) every row is also compared with
// the frames of the sensor's last fused cycle: static_bits gets the largest
// |frame - previous| per tile, in units of the noise of a difference of two
// frames (sqrt 2 times the tile's).
#define BUFFERS(X) X(0, uint, frame_words) X(1, uint, mean_words) X(2, float, inv_noise) X(3, uint, score_bits) \
    X(4, uint, previous_words) X(5, uint, static_bits)
#include "bindings.glsl"
layout(local_size_x = 32) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint width;
    uint height;
    uint channels;
    uint frames;   // K
    uint aligned;  // width % 4 == 0: a row's samples fill whole words
    uint previous; // also compare with the previous fused frames
} pc;

const uint TILE = uint(VKFUSE_SKIP_TILE);

uint frame_byte(uint i) { return (BUF(frame_words).v[i >> 2u] >> ((i & 3u) * 8u)) & 255u; }
uint mean_u16(uint i) { return (BUF(mean_words).v[i >> 1u] >> ((i & 1u) * 16u)) & 65535u; }
uint distance(uint frame_level, uint mean) {
    uint f = frame_level << 8u;
    return f > mean ? f - mean : mean - f;
}
uint previous_byte(uint i) { return (BUF(previous_words).v[i >> 2u] >> ((i & 3u) * 8u)) & 255u; }
// The largest byte-wise |a - b| of two words of four 8-bit samples.
uint byte_distance(uint a, uint b) {
    uvec4 x = (uvec4(a) >> uvec4(0u, 8u, 16u, 24u)) & 255u, y = (uvec4(b) >> uvec4(0u, 8u, 16u, 24u)) & 255u;
    uvec4 d = max(x, y) - min(x, y);
    return max(max(d.x, d.y), max(d.z, d.w));
}

// Invocation r takes row r of the tile: up to 32 pixels, 32 C samples a frame.
void main() {
    uint s = gl_WorkGroupID.z, K = pc.frames, C = pc.channels;
    uint tiles = gl_NumWorkGroups.x * gl_NumWorkGroups.y, tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint y = gl_WorkGroupID.y * TILE + gl_LocalInvocationID.x, x = gl_WorkGroupID.x * TILE;
    if (y >= pc.height) return;
    uint n = min(TILE, pc.width - x) * C;  // samples of this row in the tile
    uint run = (y * pc.width + x) * C, frame_samples = pc.width * pc.height * C;
    float score = 0.0, still = 0.0;
    for (uint k = 0u; k < K; ++k) {
        uint f = s * K + k, first = f * frame_samples + run, worst = 0u, moved = 0u;
        if (pc.aligned != 0u) {  // n / 4 words of frame, n / 2 of means
            for (uint w = 0u; w < n / 4u; ++w) {
                uint bytes = BUF(frame_words).v[first / 4u + w];
                uint lo = BUF(mean_words).v[first / 2u + 2u * w], hi = BUF(mean_words).v[first / 2u + 2u * w + 1u];
                worst = max(worst, distance(bytes & 255u, lo & 65535u));
                worst = max(worst, distance((bytes >> 8u) & 255u, lo >> 16u));
                worst = max(worst, distance((bytes >> 16u) & 255u, hi & 65535u));
                worst = max(worst, distance(bytes >> 24u, hi >> 16u));
                if (pc.previous != 0u) moved = max(moved, byte_distance(bytes, BUF(previous_words).v[first / 4u + w]));
            }
        } else {
            for (uint j = 0u; j < n; ++j) {
                uint level = frame_byte(first + j);
                worst = max(worst, distance(level, mean_u16(first + j)));
                if (pc.previous != 0u) {
                    uint before = previous_byte(first + j);
                    moved = max(moved, max(level, before) - min(level, before));
                }
            }
        }
        float inv = BUF(inv_noise).v[f * tiles + tile];
        score = max(score, float(worst) * inv);
        still = max(still, float(moved << 8u) * inv * 0.70710678);
    }
    if (score > 0.0) atomicMax(BUF(score_bits).v[s * tiles + tile], floatBitsToUint(score));
    if (still > 0.0) atomicMax(BUF(static_bits).v[s * tiles + tile], floatBitsToUint(still));
}

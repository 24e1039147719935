#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// A skipping plan's decision, taken on the device so that detection, the
// decision, compaction and fusion are one submit (SkipPolicy::Idle;
// vk/plan/plan_skip.hpp has the pass chain). One workgroup:
//  1. sensor s is fused when a tile's score exceeds the threshold: the host's
//     rule !(score <= threshold), with pc.threshold the largest float not
//     above the plan's, so that both decide alike on every float score;
//  2. the fused sensors take slots 0..F-1 in sensor order (a serial scan:
//     sensors are few), and a slot whose sensor or background changed since
//     it last held one is listed for a background copy;
//  3. every indirect dispatch gets its groups: a fusion dispatch z = F times
//     its z per sensor, the frame gathers the slots g..F-1 that are not their
//     own sensor's, the background gather the listed slots.
#define BUFFERS(X) X(0, uint, score_bits) X(1, uint, host_args) X(2, uint, decision) X(3, uint, indirect)
#include "bindings.glsl"
layout(local_size_x = 64) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    uint sensors;
    uint tiles;
    uint gather_args;  // index of the three gathers' commands in `indirect`
    uint backgrounds;  // the plan keeps a background per slot
    float threshold;
} pc;
#include "skip_decision.glsl"

shared uint fused_count;

void main() {
    uint S = pc.sensors, t = gl_LocalInvocationID.x;
    for (uint s = t; s < S; s += 64u) {
        bool changed = false;
        for (uint i = 0u; i < pc.tiles && !changed; ++i)
            changed = !(uintBitsToFloat(BUF(score_bits).v[s * pc.tiles + i]) <= pc.threshold);
        BUF(decision).v[SLOT_OF(s)] = changed ? 1u : 0u;
    }
    memoryBarrierBuffer();
    barrier();
    if (t == 0u) {
        uint F = 0u, g = NOT_FUSED;
        for (uint s = 0u; s < S; ++s) {
            if (BUF(decision).v[SLOT_OF(s)] == 0u) {
                BUF(decision).v[SLOT_OF(s)] = NOT_FUSED;
                continue;
            }
            if (g == NOT_FUSED && s != F) g = F;
            BUF(decision).v[SENSOR_OF(F)] = s;
            BUF(decision).v[SLOT_OF(s)] = F;
            ++F;
        }
        if (g == NOT_FUSED) g = F;
        uint copies = 0u;
        for (uint j = 0u; j < F && pc.backgrounds != 0u; ++j) {
            uint s = BUF(decision).v[SENSOR_OF(j)], version = BUF(host_args).v[HOST_VERSION(s)];
            if (BUF(decision).v[HELD_SENSOR(j)] == s && BUF(decision).v[HELD_VERSION(j)] == version) continue;
            BUF(decision).v[COPY_LIST(copies)] = j;
            BUF(decision).v[HELD_SENSOR(j)] = s;
            BUF(decision).v[HELD_VERSION(j)] = version;
            ++copies;
        }
        BUF(decision).v[FUSED_COUNT] = F;
        BUF(decision).v[FIRST_MOVED] = g;
        BUF(decision).v[COPY_COUNT] = copies;
        uint counts[3] = uint[3](F - g, F - g, copies);
        for (uint i = 0u; i < 3u; ++i) {
            uint to = 3u * (pc.gather_args + i);
            BUF(indirect).v[to] = BUF(host_args).v[HOST_GATHER(i)];
            BUF(indirect).v[to + 1u] = BUF(host_args).v[HOST_GATHER(i) + 1u];
            BUF(indirect).v[to + 2u] = BUF(host_args).v[HOST_GATHER(i) + 2u] * counts[i];
        }
        fused_count = F;
    }
    memoryBarrierShared();
    barrier();
    uint F = fused_count, D = BUF(host_args).v[HOST_DISPATCHES];
    for (uint d = t; d < D; d += 64u) {
        BUF(indirect).v[3u * d] = BUF(host_args).v[HOST_FUSION(d)];
        BUF(indirect).v[3u * d + 1u] = BUF(host_args).v[HOST_FUSION(d) + 1u];
        BUF(indirect).v[3u * d + 2u] = BUF(host_args).v[HOST_FUSION(d) + 2u] * F;
    }
}

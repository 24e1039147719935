#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Fuses the K frames of every sensor and channel, coefficient by coefficient.
// Source planes are (sensor s, frame k, channel c) at (s*K + k)*C + c; the
// fused plane (s, c) at s*C + c. Inside the top-left split_w x split_h corner
// (a wavelet approximation, the top of a pyramid) the base rule applies, the
// detail rule elsewhere. With a table, fused sensor s takes its K frames from
// source sensor-frames table[s*K + k] (planes table[s*K + k]*C + c) instead:
// frames decomposed once, fused in many combinations (study/cached_fusion.hpp).
// Nothing is written inside the top-left skip_w x skip_h corner (a level's
// approximation that the inverse overwrites). Where rows are whole quads
// (quads: width, row_stride and plane_stride multiples of 4) an invocation
// fuses four neighbouring coefficients with plane4 loads and stores. The
// dispatch covers the fused sensors group_sensor() names (common.glsl).
layout(local_size_x = VKFUSE_LINE_GROUP) in;
#define BUFFERS(X) X(0, plane_t, src) X(1, plane_t, dst) X(2, uint, table) X(3, plane4_t, src4) X(4, plane4_t, dst4)
#include "bindings.glsl"
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int width;       // region fused per plane
    int height;
    int row_stride;  // of src and dst planes
    uint plane_stride;
    uint frames;
    uint channels;
    uint base_rule;
    uint detail_rule;
    int split_w;
    int split_h;
    uint use_table;
    int skip_w;
    int skip_h;
    uint quads;
    uint group_first;
    uint group_count;
    uint group_period;
} pc;

uint source_plane(uint s, uint k, uint c) {
    uint frame = s * pc.frames + k;
    if (pc.use_table != 0u) frame = BUF(table).v[frame];
    return frame * pc.channels + c;
}

bool base_at(int x, int y) { return x < pc.split_w && y < pc.split_h; }

void main() {
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), pc.quads != 0u ? uint(pc.width) / 4u : uint(pc.width));
    int x = item.x * (pc.quads != 0u ? 4 : 1), y = item.y;
    if (x >= pc.width || y >= pc.height) return;
    int last = pc.quads != 0u ? x + 3 : x;
    if (last < pc.skip_w && y < pc.skip_h) return;
    uint c = gl_WorkGroupID.z % pc.channels;
    uint s = group_sensor(gl_WorkGroupID.z / pc.channels, pc.group_first, pc.group_count, pc.group_period);
    uint z = s * pc.channels + c;  // the fused plane
    uint offset = uint(y * pc.row_stride + x);
    if (pc.quads != 0u && base_at(x, y) == base_at(last, y)) {
        uint rule = base_at(x, y) ? pc.base_rule : pc.detail_rule;
        vec4 pick = vec4(0.0), sum = vec4(0.0);
        for (uint k = 0u; k < pc.frames; ++k)
            rule_add4(rule, pick, sum, k, vec4(BUF(src4).v[(source_plane(s, k, c) * pc.plane_stride + offset) / 4u]));
        BUF(dst4).v[(z * pc.plane_stride + offset) / 4u] = TO_PLANE4(rule_result4(rule, pc.frames, pick, sum));
        return;
    }
    for (int i = x; i <= last; ++i) {  // a quad across the base corner's edge: sample by sample
        uint rule = base_at(i, y) ? pc.base_rule : pc.detail_rule;
        uint at = offset + uint(i - x);
        RuleState st = RuleState(0.0, 0.0);
        for (uint k = 0u; k < pc.frames; ++k) rule_add(st, rule, k, BUF(src).v[source_plane(s, k, c) * pc.plane_stride + at]);
        BUF(dst).v[z * pc.plane_stride + at] = TO_PLANE(rule_result(st, rule, pc.frames));
    }
}

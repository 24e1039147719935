#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// Fuses the K frames of every sensor and channel, coefficient by coefficient.
// Source planes are (sensor s, frame k, channel c) at (s*K + k)*C + c; the
// fused plane (s, c) at s*C + c. Inside the top-left split_w x split_h corner
// (a wavelet approximation, the top of a pyramid) the base rule applies, the
// detail rule elsewhere.
layout(local_size_x = 16, local_size_y = 16) in;
#define BUFFERS(X) X(0, plane_t, src) X(1, plane_t, dst)
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
} pc;

void main() {
    int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    uint z = gl_WorkGroupID.z;  // s * C + c
    if (x >= pc.width || y >= pc.height) return;
    uint s = z / pc.channels, c = z % pc.channels;
    uint rule = (x < pc.split_w && y < pc.split_h) ? pc.base_rule : pc.detail_rule;
    uint offset = uint(y * pc.row_stride + x);
    RuleState st = RuleState(0.0, 0.0);
    for (uint k = 0u; k < pc.frames; ++k) {
        uint plane = (s * pc.frames + k) * pc.channels + c;
        rule_add(st, rule, k, BUF(src).v[plane * pc.plane_stride + offset]);
    }
    BUF(dst).v[z * pc.plane_stride + offset] = TO_PLANE(rule_result(st, rule, pc.frames));
}

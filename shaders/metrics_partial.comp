#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "reduce.glsl"
// Per-workgroup partial sums of the metrics over the fused planes of each
// sensor (workgroup z = sensor). Pass 0: (sum of gradient magnitude of luma,
// sum of luma, sum over channels of |I - B|, 0). Pass 1, once the mean luma is
// known: (sum of (Y - mean)^2, 0, 0, 0): contrast takes two passes so it never
// subtracts two large nearly equal sums.
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    Floats img;       // planes s*C + c, width x height
    Floats bg;        // background planes, same layout (if has_bg)
    Floats partials;  // vec4 per (sensor, group)
    Floats totals;    // pass 1 reads the pass-0 totals: vec4 per sensor
    int width;
    int height;
    uint channels;
    uint groups;      // workgroups per sensor
    uint has_bg;
    uint pass_index;
} pc;

const uint ITEMS = 16u;

float luma(uint base, int x, int y) {
    uint i = base + uint(y * pc.width + x);
    if (pc.channels == 1u) return pc.img.v[i];
    uint ps = uint(pc.width * pc.height);
    return 0.299 * pc.img.v[i] + 0.587 * pc.img.v[i + ps] + 0.114 * pc.img.v[i + 2u * ps];
}

// numpy.gradient along one axis: central difference inside, one-sided at the
// ends, zero on a length-1 axis.
float gradient(uint base, int x, int y, int dx, int dy, int pos, int n) {
    if (n == 1) return 0.0;
    if (pos == 0) return luma(base, x + dx, y + dy) - luma(base, x, y);
    if (pos == n - 1) return luma(base, x, y) - luma(base, x - dx, y - dy);
    return (luma(base, x + dx, y + dy) - luma(base, x - dx, y - dy)) * 0.5;
}

void main() {
    uint s = gl_WorkGroupID.z, g = gl_WorkGroupID.x;
    uint pixels = uint(pc.width * pc.height);
    uint base = s * pc.channels * pixels;
    float mean = pc.pass_index == 1u ? pc.totals.v[s * 4u + 1u] / float(pixels) : 0.0;
    precise vec4 sum = vec4(0.0), comp = vec4(0.0);
    for (uint i = 0u; i < ITEMS; ++i) {
        uint p = (g * ITEMS + i) * WG + gl_LocalInvocationIndex;
        if (p >= pixels) break;
        int y = int(p / uint(pc.width)), x = int(p % uint(pc.width));
        vec4 v = vec4(0.0);
        if (pc.pass_index == 0u) {
            float gx = gradient(base, x, y, 1, 0, x, pc.width);
            float gy = gradient(base, x, y, 0, 1, y, pc.height);
            v.x = sqrt(gx * gx + gy * gy);
            v.y = luma(base, x, y);
            if (pc.has_bg != 0u)
                for (uint c = 0u; c < pc.channels; ++c)
                    v.z += abs(pc.img.v[base + c * pixels + p] - pc.bg.v[base + c * pixels + p]);
        } else {
            float d = luma(base, x, y) - mean;
            v.x = d * d;
        }
        kahan_add(sum, comp, v);
    }
    vec4 total = workgroup_sum(sum, comp);
    if (gl_LocalInvocationIndex == 0u) {
        uint o = (s * pc.groups + g) * 4u;
        pc.partials.v[o] = total.x;
        pc.partials.v[o + 1u] = total.y;
        pc.partials.v[o + 2u] = total.z;
        pc.partials.v[o + 3u] = total.w;
    }
}

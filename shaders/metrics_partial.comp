#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "reduce.glsl"
// Per-workgroup partial sums of the metrics over the fused planes of each
// sensor (workgroup z = sensor). Pass 0: (sum of gradient magnitude of luma,
// sum of Y - Y0, sum over channels of |I - B|, sum of |Y - Y0|), Y0 being the
// sensor's first luma. Pass 1, once the mean is known: (sum of
// ((Y - Y0 - mean) * scale)^2, scale, 0, 0). Contrast takes two passes so it
// never subtracts two large nearly equal sums, and is taken about Y0 so that a
// constant image sums exact zeros (contrast exactly 0, not the rounding residue
// of its mean) and a nearly flat one sums small deviations, not its level.
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    Planes img;       // planes s*C + c, width x height
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

// Rows per invocation: an invocation walks ROWS pixels down one column,
// keeping the luma above, at and below the current pixel (and its channels)
// in registers, so each pixel's channels are loaded about three times (for
// itself and as its left and right neighbour's) instead of once per use.
const uint ROWS = 16u;

vec3 channels_at(uint base, int x, int y) {
    uint i = base + uint(y * pc.width + x);
    if (pc.channels == 1u) return vec3(pc.img.v[i], 0.0, 0.0);
    uint ps = uint(pc.width * pc.height);
    return vec3(pc.img.v[i], pc.img.v[i + ps], pc.img.v[i + 2u * ps]);
}

float luma_of(vec3 c) {
    return pc.channels == 1u ? c.x : 0.299 * c.x + 0.587 * c.y + 0.114 * c.z;
}

float luma(uint base, int x, int y) { return luma_of(channels_at(base, x, y)); }

// numpy.gradient along one axis from the samples before, at and after pos:
// central difference inside, one-sided at the ends, zero on a length-1 axis.
float gradient(float before, float here, float after, int pos, int n) {
    if (n == 1) return 0.0;
    if (pos == 0) return after - here;
    if (pos == n - 1) return here - before;
    return (after - before) * 0.5;
}

// |(gx, gy)| without squaring the components: gx * gx overflows float beyond
// 1.8e19 (a frame scaled by 1e30 gave Inf, then NaN in the Kahan sum) and
// underflows to 0 below 1e-19. Factoring out the larger one is exact up to
// rounding at every scale and keeps the result homogeneous in the frame.
float magnitude(float gx, float gy) {
    float big = max(abs(gx), abs(gy));
    if (big == 0.0) return 0.0;
    float ratio = min(abs(gx), abs(gy)) / big;
    return big * sqrt(1.0 + ratio * ratio);
}

// Pass 1 multiplies each deviation by a power of two near 1 / mean|Y - Y0| so
// that its square neither overflows (frames near 1e30) nor underflows (near
// 1e-30); a power of two changes no rounding. Clamped so the scale itself and
// its reduction stay normal floats; 1 for a constant image.
float deviation_scale(float abs_sum, uint pixels) {
    if (abs_sum == 0.0) return 1.0;
    int exponent;
    frexp(abs_sum, exponent);
    return ldexp(1.0, clamp(findMSB(pixels) - exponent, -126, 126));
}

void main() {
    // Groups come as an (x, y) grid (grid_1d(): 2^28 pixels need 65536 of
    // them, one more than x alone may hold); the few past the end leave
    // together, so the barriers below stay uniform within every group.
    uint s = gl_WorkGroupID.z, g = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (g >= pc.groups) return;
    uint pixels = uint(pc.width * pc.height);
    uint base = s * pc.channels * pixels;
    float y0 = luma(base, 0, 0);
    float mean = 0.0, scale = 1.0;
    if (pc.pass_index == 1u) {
        mean = pc.totals.v[s * 4u + 1u] / float(pixels);
        scale = deviation_scale(pc.totals.v[s * 4u + 3u], pixels);
    }
    // Item = (strip, column); lanes of a group take neighbouring columns.
    uint item = g * WG + gl_LocalInvocationIndex;
    int x = int(item % uint(pc.width));
    int top = int(item / uint(pc.width) * ROWS);
    int xl = max(x - 1, 0), xr = min(x + 1, pc.width - 1);
    precise vec4 sum = vec4(0.0), comp = vec4(0.0);
    vec3 here = vec3(0.0);
    float above = 0.0, at = 0.0;
    if (top < pc.height) {
        here = channels_at(base, x, top);
        at = luma_of(here);
        above = top > 0 ? luma(base, x, top - 1) : at;
    }
    for (uint r = 0u; r < ROWS; ++r) {
        int y = top + int(r);
        if (y >= pc.height) break;
        vec3 next = y + 1 < pc.height ? channels_at(base, x, y + 1) : here;
        float below = luma_of(next);
        vec4 v = vec4(0.0);
        if (pc.pass_index == 0u) {
            float gx = gradient(luma(base, xl, y), at, luma(base, xr, y), x, pc.width);
            float gy = gradient(above, at, below, y, pc.height);
            v.x = magnitude(gx, gy);
            v.y = at - y0;
            if (pc.has_bg != 0u) {
                uint p = uint(y * pc.width + x);
                for (uint c = 0u; c < pc.channels; ++c)
                    v.z += abs(here[c] - pc.bg.v[base + c * pixels + p]);
            }
            v.w = abs(v.y);
        } else {
            float d = (at - y0 - mean) * scale;
            v.x = d * d;
            // The host divides the scale back out: it travels as a sum with one
            // non-zero term, so the value the host reads is the one used here.
            v.y = (x == 0 && y == 0) ? scale : 0.0;
        }
        kahan_add(sum, comp, v);
        above = at;
        at = below;
        here = next;
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

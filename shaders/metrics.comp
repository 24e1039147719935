#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
// The metrics a plan asked for, in one pass over the fused planes (s*C + c; workgroup z =
// sensor s). Each workgroup writes one partial of 8 floats straight into the
// host-visible read-back buffer:
//   (sum of gradient magnitude of luma, sum over channels of |I - B|,
//    n, mean of d, sum of (d - mean)^2, 0, 0, 0)
// over its n pixels, with d = Y - Y0 and Y0 the sensor's first luma. The host
// adds the partials in double (Plan::metrics), the last two with Chan's
// pairwise update, so contrast needs no second pass: Welford's update keeps
// every term a deviation from a running mean, never a difference of two large
// sums; taken about Y0, a constant image sums exact zeros (contrast exactly
// 0) and a nearly flat one small deviations, not its level.
//
// Where rows are whole quads it also writes the fused image the host reads
// (HWC float32, frames.glsl), which spares pack.comp its pass over the planes.
//
// An invocation walks ROWS rows down a strip 4 pixels wide, keeping the luma
// of the rows above, at and below in registers: per row one plane4 per
// channel (and per background channel) plus the two side neighbours' channels.
#define BUFFERS(X) X(0, plane_t, img) X(1, plane4_t, img4) X(2, float, bg) X(3, vec4, bg4) X(4, vec4, partials) \
    X(5, float, image) X(6, vec4, image_quads)
#include "bindings.glsl"
layout(local_size_x = 256) in;
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int width;
    int height;
    uint channels;
    uint groups;  // workgroups per sensor
    uint has_bg;
    uint want_sharpness;  // the gradient pass: a plan asked for sharpness
    uint want_contrast;   // the luma moments: a plan asked for contrast
    uint quads;   // width % 4 == 0: rows are whole plane4 elements
    uint pixels;  // width * height
    uint write_image;  // quads only: also pack the planes into the read-back image (pack.comp's work)
    uint bg_group;     // sensors sharing a background: sensor s's is the planes of s - s % bg_group in bg
} pc;
#define VKFUSE_WRITES_IMAGES
#include "frames.glsl"

const uint WG = 256u;
const int ROWS = VKFUSE_METRIC_ROWS;

uint plane_size() { return uint(pc.width * pc.height); }

// Channel c of pixels x .. x+3 of row y (entries past the row's end: 0).
vec4 quad(uint base, uint c, int x, int y) {
    uint i = base + c * plane_size() + uint(y * pc.width + x);
    if (pc.quads != 0u) return vec4(BUF(img4).v[i / 4u]);
    vec4 q = vec4(0.0);
    for (int p = 0; p < 4 && x + p < pc.width; ++p) q[p] = float(BUF(img).v[i + uint(p)]);
    return q;
}

vec4 bg_quad(uint base, uint c, int x, int y) {
    uint i = base + c * plane_size() + uint(y * pc.width + x);
    if (pc.quads != 0u) return BUF(bg4).v[i / 4u];
    vec4 q = vec4(0.0);
    for (int p = 0; p < 4 && x + p < pc.width; ++p) q[p] = BUF(bg).v[i + uint(p)];
    return q;
}

float luma_at(uint base, int x, int y) {
    uint i = base + uint(y * pc.width + x);
    if (pc.channels == 1u) return float(BUF(img).v[i]);
    uint ps = plane_size();
    return 0.299 * float(BUF(img).v[i]) + 0.587 * float(BUF(img).v[i + ps]) + 0.114 * float(BUF(img).v[i + 2u * ps]);
}

vec4 luma_quad(vec4 r, vec4 g, vec4 b) {
    return pc.channels == 1u ? r : 0.299 * r + 0.587 * g + 0.114 * b;
}

// numpy.gradient along one axis from the samples before, at and after pos:
// central difference inside, one-sided at the ends, zero on a length-1 axis.
float gradient(float before, float here, float after, int pos, int n) {
    if (n == 1) return 0.0;
    if (pos == 0) return after - here;
    if (pos == n - 1) return here - before;
    return (after - before) * 0.5;
}

// |(gx, gy)| without squaring the components (no overflow or underflow at any
// scale): the larger one factored out, exact up to rounding.
float magnitude(float gx, float gy) {
    float big = max(abs(gx), abs(gy));
    if (big == 0.0) return 0.0;
    float ratio = min(abs(gx), abs(gy)) / big;
    return big * sqrt(1.0 + ratio * ratio);
}

struct Moments {
    float n, mean, m2;
};

// Chan, Golub and LeVeque's pairwise update: a and b's pixels together.
Moments combine(Moments a, Moments b) {
    float n = a.n + b.n;
    if (b.n == 0.0) return a;
    if (a.n == 0.0) return b;
    float delta = b.mean - a.mean;
    float share = b.n / n;
    return Moments(n, a.mean + delta * share, a.m2 + b.m2 + delta * delta * a.n * share);
}

shared vec2 shared_sums[WG];
shared vec3 shared_moments[WG];
const uint SPAN = 16u;  // WG = SPAN * SPAN

// Result i of the workgroup's into a running total.
void add_shared(inout vec2 sums, inout Moments m, uint i) {
    sums += shared_sums[i];
    vec3 b = shared_moments[i];
    m = combine(m, Moments(b.x, b.y, b.z));
}

void kahan_add(inout vec2 sum, inout vec2 comp, vec2 v) {
    precise vec2 y = v - comp;
    precise vec2 t = sum + y;
    comp = (t - sum) - y;
    sum = t;
}

void main() {
    // Groups come as an (x, y) grid (grid_1d()); the few past the end leave
    // together, so the barriers below stay uniform within every group.
    uint s = gl_WorkGroupID.z, g = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (g >= pc.groups) return;
    uint C = pc.channels, base = s * C * plane_size(), bg_base = (s - s % pc.bg_group) * C * plane_size();
    uint quads_per_row = uint(pc.width + 3) / 4u;
    uint item = g * WG + gl_LocalInvocationIndex;
    int x = int(item % quads_per_row) * 4;
    int top = int(item / quads_per_row) * ROWS;
    float y0 = luma_at(base, 0, 0);
    precise vec2 sums = vec2(0.0), comp = vec2(0.0);  // (gradient magnitude, |I - B|)
    Moments m = Moments(0.0, 0.0, 0.0);
    if (top < pc.height) {
        vec4 r = quad(base, 0u, x, top), gr = C == 3u ? quad(base, 1u, x, top) : r, b = C == 3u ? quad(base, 2u, x, top) : r;
        vec4 at = luma_quad(r, gr, b);
        vec4 above = at;
        if (top > 0) {
            vec4 r1 = quad(base, 0u, x, top - 1);
            above = C == 3u ? luma_quad(r1, quad(base, 1u, x, top - 1), quad(base, 2u, x, top - 1)) : r1;
        }
        for (int row = 0; row < ROWS; ++row) {
            int y = top + row;
            if (y >= pc.height) break;
            if (pc.write_image != 0u) store_image_quad(s, uint(y * pc.width + x) / 4u, Quad(r, gr, b));
            vec4 below = at, nr = r, ng = gr, nb = b;
            if (y + 1 < pc.height) {
                nr = quad(base, 0u, x, y + 1);
                ng = C == 3u ? quad(base, 1u, x, y + 1) : nr;
                nb = C == 3u ? quad(base, 2u, x, y + 1) : nr;
                below = luma_quad(nr, ng, nb);
            }
            float left = 0.0, right = 0.0;
            if (pc.want_sharpness != 0u) {
                left = x > 0 ? luma_at(base, x - 1, y) : 0.0;
                right = x + 4 < pc.width ? luma_at(base, x + 4, y) : 0.0;
            }
            vec4 d = vec4(0.0);
            if (pc.has_bg != 0u) {
                d = abs(r - bg_quad(bg_base, 0u, x, y));
                if (C == 3u) d += abs(gr - bg_quad(bg_base, 1u, x, y)) + abs(b - bg_quad(bg_base, 2u, x, y));
            }
            for (int p = 0; p < 4; ++p) {
                if (x + p >= pc.width) break;
                float g = 0.0;
                if (pc.want_sharpness != 0u) {
                    float before = p == 0 ? left : at[p - 1], after = p == 3 ? right : at[p + 1];
                    g = magnitude(gradient(before, at[p], after, x + p, pc.width),
                                  gradient(above[p], at[p], below[p], y, pc.height));
                }
                kahan_add(sums, comp, vec2(g, d[p]));
                if (pc.want_contrast == 0u) continue;
                // Welford's update of the deviations' moments.
                float dev = at[p] - y0;
                m.n += 1.0;
                float delta = dev - m.mean;
                m.mean += delta / m.n;
                m.m2 += delta * (dev - m.mean);
            }
            above = at;
            at = below;
            r = nr;
            gr = ng;
            b = nb;
        }
    }
    // The workgroup's 256 results, added in a fixed order (no atomics: the
    // same bits every run): SPAN invocations each add a run of SPAN, then the
    // first adds theirs. Two barriers rather than a binary tree's one per
    // level: on lavapipe a barrier suspends and resumes every SIMD batch of
    // the group, and each level of a tree runs its masked-off batches too.
    uint tid = gl_LocalInvocationIndex;
    shared_sums[tid] = sums - comp;
    shared_moments[tid] = vec3(m.n, m.mean, m.m2);
    barrier();
    if (tid < SPAN) {
        vec2 run = vec2(0.0);
        Moments acc = Moments(0.0, 0.0, 0.0);
        for (uint k = 0u; k < SPAN; ++k) add_shared(run, acc, tid * SPAN + k);
        shared_sums[tid * SPAN] = run;
        shared_moments[tid * SPAN] = vec3(acc.n, acc.mean, acc.m2);
    }
    barrier();
    if (tid == 0u) {
        vec2 total = vec2(0.0);
        Moments acc = Moments(0.0, 0.0, 0.0);
        for (uint k = 0u; k < SPAN; ++k) add_shared(total, acc, k * SPAN);
        uint o = (s * pc.groups + g) * 2u;
        BUF(partials).v[o] = vec4(total, acc.n, acc.mean);
        BUF(partials).v[o + 1u] = vec4(acc.m2, 0.0, 0.0, 0.0);
    }
}

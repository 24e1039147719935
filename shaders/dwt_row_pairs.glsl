// The row pass of a periodization DWT, eight (low, high) pairs at a time:
// what dwt_rows4.comp (from planes) and dwt_rows_frames.comp (from the frames
// as uploaded) share. An invocation holds the window of 2 * 8 + F - 2 samples
// its pairs read, loaded as quads where it lies inside the row, and stores
// each half as two plane4. Each output is the same rounded-once dot product
// as dwt_forward's (compensated.glsl). Needs the push fields half_len,
// dst_row_stride and dst_plane_stride, and a plane4_t buffer dst4.
const int PAIRS = VKFUSE_ROW_PAIRS;
const int SPAN = 2 * PAIRS + MAX_TAPS - 2;  // longest window
// The window starts at sample 2 o0 + 1 - F/2: SHIFT past a quad boundary.
const int SHIFT = ((1 - F / 2) % 4 + 4) % 4;
const int QUADS = (SPAN + 3 + 3) / 4;
const int WINDOW_QUADS = QUADS * 4;  // window sample i is at win[SHIFT + i]

// The first sample of the window of pairs o0 .. o0 + 7 (a multiple of 4).
int window_base(int o0) { return 2 * o0 + 1 - F / 2 - SHIFT; }

// Whether that window lies inside a row of n samples, so it loads as quads.
bool window_inside(int base, int n) { return base >= 0 && base + WINDOW_QUADS <= n; }

void store_pairs(float win[WINDOW_QUADS], uint plane, int line, int o0) {
    float lo[PAIRS], hi[PAIRS];
    [[unroll]] for (int b = 0; b < PAIRS; ++b) {
        Dot2 l = dot2_of(0.0), h = dot2_of(0.0);
        [[unroll]] for (int j = 0; j < F; ++j) {  // x[F/2 + 2o - j] is window sample 2b + F - 1 - j
            TAP_ADD(l, dec_lo(j), win[SHIFT + 2 * b + F - 1 - j]);
            TAP_ADD(h, dec_hi(j), win[SHIFT + 2 * b + F - 1 - j]);
        }
        lo[b] = dot2_result(l);
        hi[b] = dot2_result(h);
    }
    uint out_ = (plane * pc.dst_plane_stride + uint(line * pc.dst_row_stride + o0)) / 4u;
    uint high = uint(pc.half_len) / 4u;
    BUF(dst4).v[out_] = TO_PLANE4(vec4(lo[0], lo[1], lo[2], lo[3]));
    BUF(dst4).v[out_ + 1u] = TO_PLANE4(vec4(lo[4], lo[5], lo[6], lo[7]));
    BUF(dst4).v[out_ + high] = TO_PLANE4(vec4(hi[0], hi[1], hi[2], hi[3]));
    BUF(dst4).v[out_ + high + 1u] = TO_PLANE4(vec4(hi[4], hi[5], hi[6], hi[7]));
}

// cv::pyrUp for 2 x 8 outputs at once: rows 2i, 2i + 1 and columns 2j .. 2j+7
// from the 3 x 6 source samples (rows i - 1 reflected, i, i + 1 clamped;
// columns j - 1 .. j + 4) they draw on, j a multiple of 4 in a plane whose
// width cw is one too. pyr_up_block (common.glsl) lane by lane, with the same
// sums in the same order. The including kernel has push fields cw and ch and
// defines a reader of source rows per source it walks with PYR_UP_ROW.

struct Up4 {
    vec4 even0, odd0;  // output row 2i: columns 2(j+t) and 2(j+t) + 1
    vec4 even1, odd1;  // output row 2i + 1
};

// Horizontal pyrUp sums of one source row for even and odd output columns.
void up_h(float left, vec4 q, float right, out vec4 even, out vec4 odd) {
    vec4 l = vec4(left, q.xyz), r = vec4(q.yzw, right);
    even = (1.0 * l + 6.0 * q) + 1.0 * r;
    odd = 4.0 * q + 4.0 * r;
}

// A source row's horizontal sums: even and odd output columns.
struct UpRow {
    vec4 even, odd;
};

// Defines `UpRow FN(uint base, int r, int j)`: source row r's sums, from the
// plane at `base` of the buffers PLANE (plane_t) and PLANE4 (plane4_t), whose
// planes are cw x ch. Row r's samples j-1 .. j+4 as (left, quad, right),
// borders as OpenCV's: left of column 0 is column 1, right of the last the last.
#define PYR_UP_ROW(FN, PLANE, PLANE4)                                                       \
    UpRow FN(uint base, int r, int j) {                                                     \
        uint row = base + uint(r * pc.cw);                                                  \
        vec4 q = vec4(BUF(PLANE4).v[(row + uint(j)) / 4u]);                                 \
        float left = j == 0 ? q.y : float(BUF(PLANE).v[row + uint(j - 1)]);                 \
        float right = j + 4 < pc.cw ? float(BUF(PLANE).v[row + uint(j + 4)]) : q.w;        \
        UpRow u;                                                                            \
        up_h(left, q, right, u.even, u.odd);                                                \
        return u;                                                                           \
    }

// The vertical pass over source rows i - 1 (a), i (b) and i + 1 (c), borders
// already applied to which rows they are.
Up4 pyr_up_rows(UpRow a, UpRow b, UpRow c) {
    Up4 u;
    if (pc.ch == 1) {
        u.even0 = 8.0 * b.even * (1.0 / 64.0);
        u.odd0 = 8.0 * b.odd * (1.0 / 64.0);
        u.even1 = u.even0;
        u.odd1 = u.odd0;
        return u;
    }
    u.even0 = ((1.0 * a.even + 6.0 * b.even) + 1.0 * c.even) * (1.0 / 64.0);
    u.odd0 = ((1.0 * a.odd + 6.0 * b.odd) + 1.0 * c.odd) * (1.0 / 64.0);
    u.even1 = (4.0 * b.even + 4.0 * c.even) * (1.0 / 64.0);
    u.odd1 = (4.0 * b.odd + 4.0 * c.odd) * (1.0 / 64.0);
    return u;
}

// Source row i's neighbours as OpenCV's pyrUp borders take them: above row 0
// is row 1 (reflect-101), below the last row is the last row.
int up_row_above(int i) { return i == 0 ? min(1, pc.ch - 1) : i - 1; }
int up_row_below(int i) { return min(i + 1, pc.ch - 1); }

// Output columns 2j .. 2j+7 of one row as two quads, from its even and odd sums.
vec4 interleave_lo(vec4 even, vec4 odd) { return vec4(even.x, odd.x, even.y, odd.y); }
vec4 interleave_hi(vec4 even, vec4 odd) { return vec4(even.z, odd.z, even.w, odd.w); }

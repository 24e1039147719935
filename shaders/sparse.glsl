// Tile-sparse fusion (src/vk/passes/plan_sparse.hpp): a dispatch whose push field
// `region` is not 0 computes, for the sensor in slot z / slot_planes, only
// what its region record names. Record (8 uints from regions[region - 1 + 8 *
// slot]): line start, line count, block start, block count, half, sensor,
// full, 0. Lines and blocks are circular ranges (they wrap past the edge, as
// the periodic taps do): invocation (line i, block b) takes line
// (start + i) mod lines and block (start + b) mod blocks. With half != 0 the
// lines come in two halves of `half` (a band's low and high columns), each
// taking the range. region 0: every line and block, as recorded.
// Needs the push fields region and slot_planes and a uint buffer regions.
const uint SPARSE_RECORD = 8u;

uint sparse_record(uint z) { return pc.region - 1u + SPARSE_RECORD * (z / pc.slot_planes); }

// start + i on a circle of n (start < n, i < n), without a division: lavapipe
// runs integer division a lane at a time.
int sparse_wrap(int start, int i, int n) { return start + i >= n ? start + i - n : start + i; }

// Maps an invocation's (line, block) to the ones it computes; false: none.
bool sparse_place(uint z, inout int line, inout int block, int lines, int blocks) {
    if (pc.region == 0u) return line < lines && block < blocks;
    uint at = sparse_record(z);
    int line_count = int(BUF(regions).v[at + 1u]), block_count = int(BUF(regions).v[at + 3u]);
    int half_lines = int(BUF(regions).v[at + 4u]);
    if (block >= block_count) return false;
    block = sparse_wrap(int(BUF(regions).v[at + 2u]), block, blocks);
    int start = int(BUF(regions).v[at]);
    if (half_lines == 0) {
        if (line >= line_count) return false;
        line = sparse_wrap(start, line, lines);
        return true;
    }
    if (line >= 2 * line_count) return false;
    int upper = line >= line_count ? 1 : 0;
    line = upper * half_lines + sparse_wrap(start, line - upper * line_count, half_lines);
    return true;
}

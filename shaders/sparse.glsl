// Tile-sparse fusion (src/vk/passes/plan_sparse.hpp): a dispatch whose push field
// `region` is not 0 computes, for the sensor in slot z / slot_planes, only
// what its region record names. Record (8 uints from regions[region - 1 + 8 *
// slot]): line start, line count, block start, block count, half, sensor,
// full, 0. Lines and blocks are circular ranges (they wrap past the edge, as
// the periodic taps do): item (line i, block b) takes line
// (start + i) mod lines and block (start + b) mod blocks. With half != 0 the
// lines come in two halves of `half` (a band's low and high columns), each
// taking the range. region 0: every line and block, as recorded.
// Needs the push fields region and slot_planes and a uint buffer regions.
const uint SPARSE_RECORD = 8u;

uint sparse_record(uint z) { return pc.region - 1u + SPARSE_RECORD * (z / pc.slot_planes); }

// start + i on a circle of n (start < n, i < n), without a division: lavapipe
// runs integer division a lane at a time.
int sparse_wrap(int start, int i, int n) { return start + i >= n ? start + i - n : start + i; }

// The (line, block) an invocation of a line kernel computes; false: none.
// Line kernels are 1-D (VKFUSE_LINE_GROUP invocations a group; common.glsl's
// grid_item), since a coarse level's line is a few blocks long: an item of a
// grid of lines x blocks, lines the faster axis where lines_fastest (column
// passes: neighbours read adjacent columns). With a region
// the grid is the record's lines x blocks (two halves of lines where half !=
// 0), mapped onto the whole line as the record says.
bool line_item(uint z, bool lines_fastest, int lines, int blocks, out int line, out int block) {
    int line_count = lines, block_count = blocks, half_lines = 0;
    uint at = 0u;
    if (pc.region != 0u) {
        at = sparse_record(z);
        half_lines = int(BUF(regions).v[at + 4u]);
        line_count = int(BUF(regions).v[at + 1u]) * (half_lines != 0 ? 2 : 1);
        block_count = int(BUF(regions).v[at + 3u]);
    }
    uint fast = uint(lines_fastest ? line_count : block_count);
    if (fast == 0u) return false;
    ivec2 item = grid_item(uint(VKFUSE_LINE_GROUP), fast);
    line = lines_fastest ? item.x : item.y;
    block = lines_fastest ? item.y : item.x;
    if (line >= line_count || block >= block_count) return false;
    if (pc.region == 0u) return true;
    block = sparse_wrap(int(BUF(regions).v[at + 2u]), block, blocks);
    int start = int(BUF(regions).v[at]);
    if (half_lines == 0) {
        line = sparse_wrap(start, line, lines);
        return true;
    }
    int half_count = line_count / 2;
    int upper = line >= half_count ? 1 : 0;
    line = upper * half_lines + sparse_wrap(start, line - upper * half_count, half_lines);
    return true;
}

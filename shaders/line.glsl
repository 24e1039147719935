// 1-D transforms along rows or columns of a set of planes. A "line" is a row
// (elements 1 apart) or a column (elements row_stride apart); the same kernel
// serves both axes through these strides.
// scheme: lifting kernels' lifting scheme (lifting.glsl); unused by the convolutions.
// regions: tile-sparse fusion's records (sparse.glsl); unused by the lifting kernels.
#define BUFFERS(X) X(0, plane_t, src) X(1, plane_t, dst) X(2, float, scheme) X(3, uint, regions)
#include "bindings.glsl"
layout(push_constant, std430) uniform Push {
    BUFFER_FIELDS
    int n;            // samples per input line (forward) / output samples kept (inverse)
    int half_len;     // coefficients in the low half; the high half starts here
    int high_len;     // coefficients in the high half
    int lines;
    int src_line_stride;
    int src_elem_stride;
    uint src_plane_stride;
    int dst_line_stride;
    int dst_elem_stride;
    uint dst_plane_stride;
    uint lines_fastest;  // 1: neighbouring invocations take neighbouring lines (column passes, for coalescing)
    uint region;      // sparse.glsl (convolutions only)
    uint slot_planes; // planes per sensor
} pc;

uint src_at(uint plane, int line, int i) {
    return plane * pc.src_plane_stride + uint(line * pc.src_line_stride + i * pc.src_elem_stride);
}
uint dst_at(uint plane, int line, int i) {
    return plane * pc.dst_plane_stride + uint(line * pc.dst_line_stride + i * pc.dst_elem_stride);
}

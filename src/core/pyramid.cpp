// cv::pyrDown / cv::pyrUp in gather form; the formulas are in pyramid.hpp.
// Both are separable, so each is computed as a horizontal gather pass followed
// by a vertical one (as OpenCV does): 10 taps per pixel instead of 25 for
// pyrDown, which matters for the 4096 x 4096 reference runs.
#include "core/pyramid.hpp"

#include "core/border.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

namespace vkfuse::core {
namespace {

// The source indices and weights one output sample gathers along one axis.
struct Taps {
    std::array<int, 5> index{};
    std::array<double, 5> weight{};
    int count = 0;
};

constexpr std::array<double, 5> kDownKernel{1.0 / 16, 4.0 / 16, 6.0 / 16, 4.0 / 16, 1.0 / 16};

Taps down_taps(int x, int n) {
    Taps t;
    t.count = 5;
    for (int b = 0; b < 5; ++b) {
        t.index[b] = reflect101(2 * x + b - 2, n);
        t.weight[b] = kDownKernel[b];
    }
    return t;
}

// OpenCV's pyrUp edge rule (see pyramid.hpp): reflect-101 before the start,
// replicate past the end.
int up_edge(int i, int n) {
    if (i < 0) return std::min(1, n - 1);
    if (i >= n) return n - 1;
    return i;
}

Taps up_taps(int X, int n) {
    const int j = X / 2;
    if (X % 2 == 0) return {{up_edge(j - 1, n), j, up_edge(j + 1, n)}, {1.0 / 8, 6.0 / 8, 1.0 / 8}, 3};
    return {{j, up_edge(j + 1, n)}, {0.5, 0.5}, 2};
}

template <class TapFn>
Plane gather_rows(const Plane& src, int out_width, TapFn taps_for) {
    std::vector<Taps> taps(out_width);
    for (int x = 0; x < out_width; ++x) taps[x] = taps_for(x, src.width);
    Plane out(src.height, out_width);
    for (int y = 0; y < src.height; ++y)
        for (int x = 0; x < out_width; ++x) {
            const Taps& t = taps[x];
            double sum = 0;
            for (int b = 0; b < t.count; ++b) sum += t.weight[b] * src.at(y, t.index[b]);
            out.at(y, x) = sum;
        }
    return out;
}

template <class TapFn>
Plane gather_columns(const Plane& src, int out_height, TapFn taps_for) {
    Plane out(out_height, src.width);
    for (int y = 0; y < out_height; ++y) {
        const Taps t = taps_for(y, src.height);
        for (int x = 0; x < src.width; ++x) {
            double sum = 0;
            for (int a = 0; a < t.count; ++a) sum += t.weight[a] * src.at(t.index[a], x);
            out.at(y, x) = sum;
        }
    }
    return out;
}

}  // namespace

Plane pyr_down(const Plane& src) {
    const Plane horizontal = gather_rows(src, (src.width + 1) / 2, down_taps);
    return gather_columns(horizontal, (src.height + 1) / 2, down_taps);
}

Plane pyr_up(const Plane& src, int dst_h, int dst_w) {
    const auto fits = [](int dst, int n) { return dst == 2 * n || dst == 2 * n - 1; };
    if (!fits(dst_h, src.height) || !fits(dst_w, src.width))
        throw std::invalid_argument("pyr_up: destination size must be 2n or 2n-1 per axis");
    const Plane horizontal = gather_rows(src, dst_w, up_taps);
    return gather_columns(horizontal, dst_h, up_taps);
}

}  // namespace vkfuse::core

// Separable multi-level 2-D DWT (pywt.wavedec2 / waverec2 with axes (0, 1)),
// composed from one-axis levels of either mode; axis order and cropping as in
// wavelet.hpp.
#include "core/wavelet.hpp"
#include "core/wavelet_axis.hpp"

namespace vkfuse::core {
namespace {

Bands split(const Plane& p, int axis, Wavelet w, WaveletMode mode) {
    return mode == WaveletMode::Periodization ? split_axis_periodization(p, axis, filter_bank(w))
                                              : split_axis_lifting(p, axis, lifting_scheme(w));
}

Plane merge(const Plane& lo, const Plane& hi, int axis, Wavelet w, WaveletMode mode) {
    return mode == WaveletMode::Periodization ? merge_axis_periodization(lo, hi, axis, filter_bank(w))
                                              : merge_axis_lifting(lo, hi, axis, lifting_scheme(w));
}

}  // namespace

WaveletCoeffs wavedec2(const Plane& plane, Wavelet w, WaveletMode mode, int levels) {
    WaveletCoeffs c;
    Plane a = plane;
    for (int l = 0; l < levels; ++l) {
        const Bands rows = split(a, 0, w, mode);         // axis 0 first, like pywt.dwtn
        Bands low = split(rows.lo, 1, w, mode);          // 'aa', 'ad'
        Bands high = split(rows.hi, 1, w, mode);         // 'da', 'dd'
        c.levels.push_back({a.height, a.width, std::move(high.lo), std::move(low.hi), std::move(high.hi)});
        a = std::move(low.lo);
    }
    c.approx = std::move(a);
    return c;
}

Plane waverec2(const WaveletCoeffs& c, Wavelet w, WaveletMode mode) {
    Plane a = c.approx;
    for (auto level = c.levels.rbegin(); level != c.levels.rend(); ++level) {
        const Plane low = merge(a, level->vertical, 1, w, mode);  // axis 1 first, like pywt.idwtn
        const Plane high = merge(level->horizontal, level->diagonal, 1, w, mode);
        // Periodization returns even sizes; keeping the top-left h x w is
        // waverec2's approximation trim and the final crop to the input shape.
        a = crop(merge(low, high, 0, w, mode), level->height, level->width);
    }
    return a;
}

}  // namespace vkfuse::core

// Separable multi-level 2-D DWT (pywt.wavedec2 / waverec2 with axes (0, 1)) on
// top of the 1-D transforms of either mode; axis order and cropping as in
// wavelet.hpp.
#include <stdexcept>
#include <vector>

#include "core/wavelet.hpp"

namespace vkfuse::core {
namespace {

// The 1-D transform of one mode, with the band lengths it produces.
struct LineTransform {
    WaveletMode mode;
    const FilterBank& fb;
    const LiftingScheme& ls;

    bool periodic() const { return mode == WaveletMode::Periodization; }
    int lo_len(int n) const { return (n + 1) / 2; }
    int hi_len(int n) const { return periodic() ? (n + 1) / 2 : n / 2; }
    int out_len(int lo, int hi) const { return periodic() ? 2 * lo : lo + hi; }

    void forward(std::span<const double> x, std::span<double> lo, std::span<double> hi) const {
        if (periodic())
            dwt_periodization(x, fb, lo, hi);
        else
            dwt_lifting(x, ls, lo, hi);
    }
    void inverse(std::span<const double> lo, std::span<const double> hi, std::span<double> out) const {
        if (periodic())
            idwt_periodization(lo, hi, fb, out);
        else
            idwt_lifting(lo, hi, ls, out);
    }
};

struct Split {
    Plane lo, hi;
};

// Row y (axis 1) or column x (axis 0) of a plane, copied out and back, so the
// 1-D transforms only ever see contiguous lines.
std::vector<double> read_line(const Plane& p, int axis, int i) {
    std::vector<double> line(axis == 0 ? p.height : p.width);
    for (std::size_t k = 0; k < line.size(); ++k) line[k] = axis == 0 ? p.at(int(k), i) : p.at(i, int(k));
    return line;
}

void write_line(Plane& p, int axis, int i, const std::vector<double>& line) {
    for (std::size_t k = 0; k < line.size(); ++k) (axis == 0 ? p.at(int(k), i) : p.at(i, int(k))) = line[k];
}

Plane with_axis_length(const Plane& like, int axis, int n) {
    return axis == 0 ? Plane(n, like.width) : Plane(like.height, n);
}

Split split(const Plane& p, int axis, const LineTransform& t) {
    const int n = axis == 0 ? p.height : p.width;
    const int lines = axis == 0 ? p.width : p.height;
    Split s{with_axis_length(p, axis, t.lo_len(n)), with_axis_length(p, axis, t.hi_len(n))};
    std::vector<double> lo(t.lo_len(n)), hi(t.hi_len(n));
    for (int i = 0; i < lines; ++i) {
        t.forward(read_line(p, axis, i), lo, hi);
        write_line(s.lo, axis, i, lo);
        write_line(s.hi, axis, i, hi);
    }
    return s;
}

Plane merge(const Plane& lo, const Plane& hi, int axis, const LineTransform& t) {
    const int lines = axis == 0 ? lo.width : lo.height;
    if ((axis == 0 ? hi.width : hi.height) != lines) throw std::logic_error("waverec2: band shapes disagree");
    const int nlo = axis == 0 ? lo.height : lo.width, nhi = axis == 0 ? hi.height : hi.width;
    if (nlo != t.lo_len(t.out_len(nlo, nhi)) || nhi != t.hi_len(t.out_len(nlo, nhi)))
        throw std::logic_error("waverec2: band lengths disagree");
    Plane out = with_axis_length(lo, axis, t.out_len(nlo, nhi));
    std::vector<double> line(t.out_len(nlo, nhi));
    for (int i = 0; i < lines; ++i) {
        t.inverse(read_line(lo, axis, i), read_line(hi, axis, i), line);
        write_line(out, axis, i, line);
    }
    return out;
}

}  // namespace

WaveletCoeffs wavedec2(const Plane& plane, Wavelet w, WaveletMode mode, int levels) {
    const LineTransform t{mode, filter_bank(w), lifting_scheme(w)};
    WaveletCoeffs c;
    Plane a = plane;
    for (int l = 0; l < levels; ++l) {
        const Split rows = split(a, 0, t);         // axis 0 first, like pywt.dwtn
        const Split low = split(rows.lo, 1, t);    // 'aa', 'ad'
        const Split high = split(rows.hi, 1, t);   // 'da', 'dd'
        c.levels.push_back({a.height, a.width, high.lo, low.hi, high.hi});
        a = low.lo;
    }
    c.approx = std::move(a);
    return c;
}

Plane waverec2(const WaveletCoeffs& c, Wavelet w, WaveletMode mode) {
    const LineTransform t{mode, filter_bank(w), lifting_scheme(w)};
    Plane a = c.approx;
    for (auto level = c.levels.rbegin(); level != c.levels.rend(); ++level) {
        const Plane low = merge(a, level->vertical, 1, t);                 // axis 1 first, like pywt.idwtn
        const Plane high = merge(level->horizontal, level->diagonal, 1, t);
        // Periodization returns even sizes; keeping the top-left h x w is
        // waverec2's approximation trim and the final crop to the input shape.
        a = crop(merge(low, high, 0, t), level->height, level->width);
    }
    return a;
}

}  // namespace vkfuse::core

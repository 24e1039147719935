// pywt's MODE_PERIODIZATION DWT and IDWT as gather tables (the formulas and
// their derivation from pywt's C loops are in wavelet.hpp). The tables are
// built once per line length; rows and columns then only multiply and add.
#include <algorithm>
#include <array>
#include <stdexcept>

#include "core/line_gather.hpp"
#include "core/wavelet_axis.hpp"

namespace vkfuse::core {
namespace {

int mod(int a, int m) { return ((a % m) + m) % m; }

int axis_length(const Plane& p, int axis) { return axis == 0 ? p.height : p.width; }

}  // namespace

// a[o] or d[o] = sum_j filter[j] * xe(mod(2o + F/2 - j, Np)), xe(t) = x[min(t, n-1)].
LineGather periodization_analysis(const std::array<double, 10>& filter, int length, int n) {
    const int padded = n + n % 2;  // odd lines repeat their last sample once
    LineGather g{(n + 1) / 2, length, {}, {}};
    for (int o = 0; o < g.outputs; ++o)
        for (int j = 0; j < length; ++j) {
            g.index.push_back(std::min(mod(2 * o + length / 2 - j, padded), n - 1));
            g.weight.push_back(filter[j]);
        }
    return g;
}

// y[i] += sum_j filter[2j + p] * c[mod(m + F/4 - j, n)], q = mod(i - s, 2n), m = q / 2, p = q % 2.
LineGather periodization_synthesis(const std::array<double, 10>& filter, int length, int n) {
    const int half = length / 2, start = length / 4;
    const int shift = half % 2 == 0 ? 1 : 0;  // pywt's one-sample output shift (db2)
    LineGather g{2 * n, half, {}, {}};
    for (int i = 0; i < 2 * n; ++i) {
        const int q = mod(i - shift, 2 * n), m = q / 2, p = q % 2;
        for (int j = 0; j < half; ++j) {
            g.index.push_back(mod(m + start - j, n));
            g.weight.push_back(filter[2 * j + p]);
        }
    }
    return g;
}

void dwt_periodization(std::span<const double> x, const FilterBank& fb, std::span<double> approx,
                       std::span<double> detail) {
    const int n = int(x.size());
    if (n < 1 || approx.size() != std::size_t(n + 1) / 2 || detail.size() != approx.size())
        throw std::invalid_argument("dwt_periodization: bad lengths");
    gather_line(periodization_analysis(fb.dec_lo, fb.length, n), x, approx, false);
    gather_line(periodization_analysis(fb.dec_hi, fb.length, n), x, detail, false);
}

void idwt_periodization(std::span<const double> approx, std::span<const double> detail, const FilterBank& fb,
                        std::span<double> out) {
    const int n = int(approx.size());
    if (n < 1 || int(detail.size()) != n || int(out.size()) != 2 * n)
        throw std::invalid_argument("idwt_periodization: bad lengths");
    gather_line(periodization_synthesis(fb.rec_lo, fb.length, n), approx, out, false);
    gather_line(periodization_synthesis(fb.rec_hi, fb.length, n), detail, out, true);
}

Bands split_axis_periodization(const Plane& p, int axis, const FilterBank& fb) {
    const int n = axis_length(p, axis);
    return {gather_axis(p, axis, periodization_analysis(fb.dec_lo, fb.length, n)),
            gather_axis(p, axis, periodization_analysis(fb.dec_hi, fb.length, n))};
}

Plane merge_axis_periodization(const Plane& lo, const Plane& hi, int axis, const FilterBank& fb) {
    const int n = axis_length(lo, axis);
    if (!lo.same_shape(hi))
        throw std::logic_error("waverec2: periodization bands differ in shape");
    Plane out = gather_axis(lo, axis, periodization_synthesis(fb.rec_lo, fb.length, n));
    gather_axis_add(hi, axis, periodization_synthesis(fb.rec_hi, fb.length, n), out);
    return out;
}

}  // namespace vkfuse::core

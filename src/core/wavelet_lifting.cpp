// The symmetric mode: lifting factorisations of the four wavelets, applied in
// place on one line with whole-sample symmetric (reflect-101) neighbours. The
// step tables are data so the GPU engine can run the same steps; wavelet.hpp
// documents them.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/border.hpp"
#include "core/wavelet_axis.hpp"

namespace vkfuse::core {
namespace {

constexpr int kOdd = 1, kEven = 0;

LiftingStep step(int parity, double c0, int o0) { return {parity, 1, {c0, 0.0}, {o0, 0}}; }
LiftingStep step(int parity, double c0, int o0, double c1, int o1) { return {parity, 2, {c0, c1}, {o0, o1}}; }

LiftingScheme haar() {
    const double r2 = std::sqrt(2.0);
    return {2, {step(kOdd, -1.0, -1), step(kEven, 0.5, +1)}, r2, -1.0 / r2};
}

// Daubechies & Sweldens' factorisation of D4, aligned so the lowpass sits on
// even samples (the search that found the alignment matched pywt's db2 on the
// line advanced by one sample).
LiftingScheme db2() {
    const double r2 = std::sqrt(2.0), r3 = std::sqrt(3.0);
    return {3,
            {step(kOdd, -r3, -1), step(kEven, r3 / 4, +1, (r3 - 2) / 4, +3), step(kOdd, 1.0, -3)},
            (r3 + 1) / r2,
            -(r3 - 1) / r2};
}

// CDF 5/3: linear predict, quarter update.
LiftingScheme bior22() {
    const double r2 = std::sqrt(2.0);
    return {2, {step(kOdd, -0.5, -1, -0.5, +1), step(kEven, 0.25, -1, 0.25, +1)}, r2, -1.0 / r2};
}

// CDF 9/7 (the JPEG 2000 irreversible transform). The four constants agree to
// 1e-16 with a refit against the exact 9/7 filters (roots of 1 + 4y + 10y^2 + 20y^3).
LiftingScheme bior44() {
    const double alpha = -1.586134342059924, beta = -0.05298011857296141;
    const double gamma = 0.8829110755309333, delta = 0.4435068520439711;
    // A constant line lifts to approx 1 + 2 beta (1 + 2 alpha) and detail ~0;
    // scaling by sqrt(2) / that makes the DC gain exactly pywt's sqrt(2).
    const double ke = std::sqrt(2.0) / (1 + 2 * beta * (1 + 2 * alpha));
    return {4,
            {step(kOdd, alpha, -1, alpha, +1), step(kEven, beta, -1, beta, +1), step(kOdd, gamma, -1, gamma, +1),
             step(kEven, delta, -1, delta, +1)},
            ke,
            -1.0 / ke};
}

int axis_length(const Plane& p, int axis) { return axis == 0 ? p.height : p.width; }

// x[q] += sign * sum_t coef[t] x[R(q + offset[t])] for every q of the step's
// parity, on every line along the axis. Along axis 0 the lines are columns,
// so whole rows are combined (contiguous inner loop).
void apply(const LiftingStep& s, Plane& p, int axis, double sign) {
    const int n = axis_length(p, axis);
    if (axis == 1) {
        for (int y = 0; y < p.height; ++y)
            for (int q = s.parity; q < n; q += 2) {
                double sum = 0;
                for (int t = 0; t < s.taps; ++t) sum += s.coef[t] * p.at(y, reflect101(q + s.offset[t], n));
                p.at(y, q) += sign * sum;
            }
        return;
    }
    std::vector<double> sum(std::size_t(p.width));
    for (int q = s.parity; q < n; q += 2) {
        std::fill(sum.begin(), sum.end(), 0.0);
        for (int t = 0; t < s.taps; ++t) {
            const double* row = &p.data[std::size_t(reflect101(q + s.offset[t], n)) * p.width];
            for (int x = 0; x < p.width; ++x) sum[x] += s.coef[t] * row[x];
        }
        double* dst = &p.data[std::size_t(q) * p.width];
        for (int x = 0; x < p.width; ++x) dst[x] += sign * sum[x];
    }
}

// Samples of one parity along the axis, each multiplied by scale.
Plane take(const Plane& p, int axis, int parity, double scale) {
    const int n = (axis_length(p, axis) + 1 - parity) / 2;
    Plane out = axis == 0 ? Plane(n, p.width) : Plane(p.height, n);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            out.at(y, x) = scale * (axis == 0 ? p.at(2 * y + parity, x) : p.at(y, 2 * x + parity));
    return out;
}

// The inverse of take: interleaves band (divided by scale) into p.
void put(const Plane& band, Plane& p, int axis, int parity, double scale) {
    for (int y = 0; y < band.height; ++y)
        for (int x = 0; x < band.width; ++x)
            (axis == 0 ? p.at(2 * y + parity, x) : p.at(y, 2 * x + parity)) = band.at(y, x) / scale;
}

// A 1 x n plane holding a line, so the 1-D transforms reuse the plane code.
Plane row_plane(std::span<const double> v) {
    Plane p(1, int(v.size()));
    std::copy(v.begin(), v.end(), p.data.begin());
    return p;
}

}  // namespace

const LiftingScheme& lifting_scheme(Wavelet w) {
    static const LiftingScheme kHaar = haar(), kDb2 = db2(), kBior22 = bior22(), kBior44 = bior44();
    switch (w) {
        case Wavelet::Haar: return kHaar;
        case Wavelet::Db2: return kDb2;
        case Wavelet::Bior22: return kBior22;
        case Wavelet::Bior44: return kBior44;
    }
    throw std::invalid_argument("lifting_scheme: invalid wavelet enumerator");
}

Bands split_axis_lifting(const Plane& p, int axis, const LiftingScheme& ls) {
    if (axis_length(p, axis) == 1) return {p, axis == 0 ? Plane(0, p.width) : Plane(p.height, 0)};  // pass through
    Plane work = p;
    for (int s = 0; s < ls.steps; ++s) apply(ls.step[s], work, axis, +1.0);
    return {take(work, axis, 0, ls.scale_even), take(work, axis, 1, ls.scale_odd)};
}

Plane merge_axis_lifting(const Plane& lo, const Plane& hi, int axis, const LiftingScheme& ls) {
    const int nlo = axis_length(lo, axis), nhi = axis_length(hi, axis), n = nlo + nhi;
    const bool across_ok = axis == 0 ? lo.width == hi.width : lo.height == hi.height;
    if (!across_ok || nlo != (n + 1) / 2) throw std::logic_error("waverec2: lifting bands differ in shape");
    if (n == 1) return lo;
    Plane work = axis == 0 ? Plane(n, lo.width) : Plane(lo.height, n);
    put(lo, work, axis, 0, ls.scale_even);
    put(hi, work, axis, 1, ls.scale_odd);
    for (int s = ls.steps - 1; s >= 0; --s) apply(ls.step[s], work, axis, -1.0);
    return work;
}

void dwt_lifting(std::span<const double> x, const LiftingScheme& ls, std::span<double> approx,
                 std::span<double> detail) {
    const std::size_t n = x.size();
    if (n < 1 || approx.size() != (n + 1) / 2 || detail.size() != n / 2)
        throw std::invalid_argument("dwt_lifting: bad lengths");
    const Bands b = split_axis_lifting(row_plane(x), 1, ls);
    std::copy(b.lo.data.begin(), b.lo.data.end(), approx.begin());
    std::copy(b.hi.data.begin(), b.hi.data.end(), detail.begin());
}

void idwt_lifting(std::span<const double> approx, std::span<const double> detail, const LiftingScheme& ls,
                  std::span<double> out) {
    const std::size_t n = approx.size() + detail.size();
    if (approx.size() != (n + 1) / 2 || out.size() != n) throw std::invalid_argument("idwt_lifting: bad lengths");
    const Plane line = merge_axis_lifting(row_plane(approx), row_plane(detail), 1, ls);
    std::copy(line.data.begin(), line.data.end(), out.begin());
}

}  // namespace vkfuse::core

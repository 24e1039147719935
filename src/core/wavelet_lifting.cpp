// The symmetric mode: lifting factorisations of the four wavelets, applied in
// place on one line with whole-sample symmetric (reflect-101) neighbours. The
// step tables are data so the GPU engine can run the same steps; wavelet.hpp
// documents them.
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/border.hpp"
#include "core/wavelet.hpp"

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

// x[q] += sign * sum_t coef[t] x[R(q + offset[t])] for every q of the step's parity.
void apply(const LiftingStep& s, std::vector<double>& x, double sign) {
    const int n = int(x.size());
    for (int q = s.parity; q < n; q += 2) {
        double sum = 0;
        for (int t = 0; t < s.taps; ++t) sum += s.coef[t] * x[reflect101(q + s.offset[t], n)];
        x[q] += sign * sum;
    }
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

void dwt_lifting(std::span<const double> x, const LiftingScheme& ls, std::span<double> approx,
                 std::span<double> detail) {
    const std::size_t n = x.size();
    if (n < 1 || approx.size() != (n + 1) / 2 || detail.size() != n / 2)
        throw std::invalid_argument("dwt_lifting: bad lengths");
    if (n == 1) {  // nothing to pair the sample with: it passes through
        approx[0] = x[0];
        return;
    }
    std::vector<double> line(x.begin(), x.end());
    for (int s = 0; s < ls.steps; ++s) apply(ls.step[s], line, +1.0);
    for (std::size_t i = 0; i < approx.size(); ++i) approx[i] = line[2 * i] * ls.scale_even;
    for (std::size_t i = 0; i < detail.size(); ++i) detail[i] = line[2 * i + 1] * ls.scale_odd;
}

void idwt_lifting(std::span<const double> approx, std::span<const double> detail, const LiftingScheme& ls,
                  std::span<double> out) {
    const std::size_t n = approx.size() + detail.size();
    if (approx.size() != (n + 1) / 2 || out.size() != n) throw std::invalid_argument("idwt_lifting: bad lengths");
    if (n == 1) {
        out[0] = approx[0];
        return;
    }
    std::vector<double> line(n);
    for (std::size_t i = 0; i < approx.size(); ++i) line[2 * i] = approx[i] / ls.scale_even;
    for (std::size_t i = 0; i < detail.size(); ++i) line[2 * i + 1] = detail[i] / ls.scale_odd;
    for (int s = ls.steps - 1; s >= 0; --s) apply(ls.step[s], line, -1.0);
    for (std::size_t i = 0; i < n; ++i) out[i] = line[i];
}

}  // namespace vkfuse::core

// pywt's MODE_PERIODIZATION DWT and IDWT of one line, in gather form (the
// formulas and their derivation from pywt's C loops are in wavelet.hpp).
#include <algorithm>
#include <stdexcept>

#include "core/wavelet.hpp"

namespace vkfuse::core {
namespace {

int mod(int a, int m) { return ((a % m) + m) % m; }

}  // namespace

void dwt_periodization(std::span<const double> x, const FilterBank& fb, std::span<double> approx,
                       std::span<double> detail) {
    const int n = int(x.size());
    const int m = (n + 1) / 2;
    if (n < 1 || int(approx.size()) != m || int(detail.size()) != m)
        throw std::invalid_argument("dwt_periodization: bad lengths");
    const int padded = n + n % 2;  // odd lines repeat their last sample once
    const int f = fb.length;
    for (int o = 0; o < m; ++o) {
        double a = 0, d = 0;
        for (int j = 0; j < f; ++j) {
            const double v = x[std::min(mod(2 * o + f / 2 - j, padded), n - 1)];
            a += fb.dec_lo[j] * v;
            d += fb.dec_hi[j] * v;
        }
        approx[o] = a;
        detail[o] = d;
    }
}

void idwt_periodization(std::span<const double> approx, std::span<const double> detail, const FilterBank& fb,
                        std::span<double> out) {
    const int n = int(approx.size());
    if (n < 1 || int(detail.size()) != n || int(out.size()) != 2 * n)
        throw std::invalid_argument("idwt_periodization: bad lengths");
    const int half = fb.length / 2;
    const int start = fb.length / 4;
    const int shift = half % 2 == 0 ? 1 : 0;  // pywt's one-sample output shift (db2)
    for (int i = 0; i < 2 * n; ++i) {
        const int q = mod(i - shift, 2 * n);
        const int m = q / 2, p = q % 2;
        double sum = 0;
        for (int j = 0; j < half; ++j) {
            const int k = mod(m + start - j, n);
            sum += fb.rec_lo[2 * j + p] * approx[k] + fb.rec_hi[2 * j + p] * detail[k];
        }
        out[i] = sum;
    }
}

}  // namespace vkfuse::core

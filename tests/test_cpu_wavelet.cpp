// The wavelet transforms of the CPU reference: periodization against
// PyWavelets' own output, symmetric lifting by its defining properties.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <regex>
#include <string>
#include <vector>

#include "core/wavelet.hpp"
#include "peer_file.hpp"
#include "test_support.hpp"

namespace vkfuse {
namespace {

using core::Plane;
using core::WaveletCoeffs;

constexpr double kPeerTolerance = 1e-6;  // docs/spec.md; the observed error is ~1e-15

const test::PeerFile& peers() {
    static const test::PeerFile file("wavelet_periodization.bin");
    return file;
}

struct WaveletCase {
    Wavelet wavelet;
    const char* name;
};
const WaveletCase kWavelets[] = {
    {Wavelet::Haar, "haar"}, {Wavelet::Db2, "db2"}, {Wavelet::Bior22, "bior2.2"}, {Wavelet::Bior44, "bior4.4"}};

Plane random_plane(int h, int w, std::uint32_t seed) { return core::extract_channel(test::random_image(h, w, 1, seed), 0); }

// The generator's reproducible perturbation: u in [-0.5, 0.5) from exact integer arithmetic.
double perturbation(std::uint64_t i, std::uint64_t band) {
    const std::uint64_t h = ((i + 1) * 2654435761ull + band * 40503ull) % (1ull << 32);
    return double(h) / 4294967296.0 - 0.5;
}

void modify(Plane& p, std::uint64_t band) {
    for (std::size_t i = 0; i < p.data.size(); ++i) p.data[i] = 0.5 * p.data[i] + perturbation(i, band);
}

// gen_vectors.py's modify(): approx band 0, level l band b -> 1 + 3 (l - 1) + b.
void modify(WaveletCoeffs& c) {
    modify(c.approx, 0);
    for (std::size_t l = 0; l < c.levels.size(); ++l) {
        modify(c.levels[l].horizontal, 1 + 3 * l + 0);
        modify(c.levels[l].vertical, 1 + 3 * l + 1);
        modify(c.levels[l].diagonal, 1 + 3 * l + 2);
    }
}

TEST(CpuWavelet, FilterBanksAreBitIdenticalToPywt) {
    for (const auto& w : kWavelets) {
        const test::PeerArray& ref = peers().at(std::string("filter_bank/") + w.name);
        const core::FilterBank& fb = core::filter_bank(w.wavelet);
        ASSERT_EQ(ref.shape[1], fb.length) << w.name;
        ASSERT_EQ(fb.length, filter_length(w.wavelet));
        const std::array<double, 10>* rows[] = {&fb.dec_lo, &fb.dec_hi, &fb.rec_lo, &fb.rec_hi};
        for (int r = 0; r < 4; ++r)
            for (int j = 0; j < fb.length; ++j) EXPECT_EQ((*rows[r])[j], ref.values[r * fb.length + j]) << w.name;
    }
}

TEST(CpuWavelet, MaxLevelsMatchPywtDwtMaxLevel) {
    for (const auto& w : kWavelets) {
        const test::PeerArray& ref = peers().at(std::string("max_level/") + w.name);
        for (int n = 1; n <= 300; ++n) {
            EXPECT_EQ(max_wavelet_levels(w.wavelet, n, n + 7), int(ref.values[n - 1])) << w.name << " n=" << n;
            EXPECT_EQ(max_wavelet_levels(w.wavelet, n + 3, n), int(ref.values[n - 1])) << w.name << " n=" << n;
        }
    }
}

TEST(CpuWavelet, PeriodizationCoefficientsMatchPywtWavedec2) {
    const std::regex key(R"((haar|db2|bior2\.2|bior4\.4)/(\d+)x(\d+)/L(\d+)/approx)");
    double worst = 0;
    int cases = 0;
    for (const auto& w : kWavelets)
        for (const auto& [name, array] : peers().all()) {
            std::smatch m;
            if (!std::regex_match(name, m, key) || m[1] != w.name) continue;
            const std::string base = std::string(w.name) + "/" + m[2].str() + "x" + m[3].str();
            const int levels = std::stoi(m[4]);
            const Plane input = peers().plane("input/" + m[2].str() + "x" + m[3].str());
            const WaveletCoeffs c = core::wavedec2(input, w.wavelet, WaveletMode::Periodization, levels);
            ASSERT_EQ(int(c.levels.size()), levels);
            double err = test::max_abs_diff(c.approx, peers().plane(name));
            for (int l = 1; l <= levels; ++l) {
                const std::string lk = base + "/L" + std::to_string(levels) + "/level" + std::to_string(l);
                err = std::max(err, test::max_abs_diff(c.levels[l - 1].horizontal, peers().plane(lk + "/h")));
                err = std::max(err, test::max_abs_diff(c.levels[l - 1].vertical, peers().plane(lk + "/v")));
                err = std::max(err, test::max_abs_diff(c.levels[l - 1].diagonal, peers().plane(lk + "/d")));
            }
            EXPECT_LE(err, kPeerTolerance) << name;
            worst = std::max(worst, err);
            ++cases;
        }
    EXPECT_EQ(cases, 15);  // every (wavelet, size) that carries at least one level
    std::printf("[peer] wavedec2 periodization: %d cases, worst |err| = %.3g\n", cases, worst);
}

TEST(CpuWavelet, PeriodizationSynthesisMatchesPywtWaverec2OfModifiedCoefficients) {
    const std::regex key(R"((haar|db2|bior2\.2|bior4\.4)/(\d+)x(\d+)/L(\d+)/rec_modified)");
    double worst = 0;
    int cases = 0;
    for (const auto& w : kWavelets)
        for (const auto& [name, array] : peers().all()) {
            std::smatch m;
            if (!std::regex_match(name, m, key) || m[1] != w.name) continue;
            const Plane input = peers().plane("input/" + m[2].str() + "x" + m[3].str());
            WaveletCoeffs c = core::wavedec2(input, w.wavelet, WaveletMode::Periodization, std::stoi(m[4]));
            modify(c);
            const double err = test::max_abs_diff(core::waverec2(c, w.wavelet, WaveletMode::Periodization),
                                                  peers().plane(name));
            EXPECT_LE(err, kPeerTolerance) << name;
            worst = std::max(worst, err);
            ++cases;
        }
    EXPECT_GE(cases, 30);
    std::printf("[peer] waverec2 periodization (modified coefficients): %d cases, worst |err| = %.3g\n", cases,
                worst);
}

TEST(CpuWavelet, PeriodizationRoundTripsEveryLength) {
    for (const auto& w : kWavelets) {
        const core::FilterBank& fb = core::filter_bank(w.wavelet);
        for (int n = 1; n <= 40; ++n) {
            const Plane x = random_plane(1, n, 100 + n);
            std::vector<double> a((n + 1) / 2), d((n + 1) / 2), y(2 * a.size());
            core::dwt_periodization(x.data, fb, a, d);
            core::idwt_periodization(a, d, fb, y);
            for (int i = 0; i < n; ++i) EXPECT_NEAR(y[i], x.data[i], 1e-12) << w.name << " n=" << n;
        }
    }
}

// The symmetric mode is not pywt's, so it is checked by what defines it:
// perfect reconstruction at every size, DC gain sqrt(2), and (away from the
// borders) the same coefficients as the periodization filters.
TEST(CpuWavelet, SymmetricLiftingRoundTripsEverySize) {
    double worst = 0;
    for (const auto& w : kWavelets)
        for (int h = 1; h <= 40; h += (h < 12 ? 1 : 3))
            for (int wd = 1; wd <= 40; wd += (wd < 12 ? 1 : 5)) {
                const Plane x = random_plane(h, wd, std::uint32_t(h * 97 + wd));
                const int most = std::max(1, max_wavelet_levels(w.wavelet, h, wd));
                for (int levels : {1, most, most + 1}) {
                    const WaveletCoeffs c = core::wavedec2(x, w.wavelet, WaveletMode::Symmetric, levels);
                    const Plane y = core::waverec2(c, w.wavelet, WaveletMode::Symmetric);
                    const double err = test::max_abs_diff(x, y);
                    ASSERT_LE(err, 1e-10) << w.name << " " << h << "x" << wd << " L=" << levels;
                    worst = std::max(worst, err);
                }
            }
    std::printf("[self] symmetric lifting round trip: worst |err| = %.3g\n", worst);
}

TEST(CpuWavelet, SymmetricBandSizesAreCeilAndFloor) {
    const Plane x = random_plane(13, 8, 5);
    const WaveletCoeffs c = core::wavedec2(x, Wavelet::Bior44, WaveletMode::Symmetric, 2);
    const core::WaveletLevel& l1 = c.levels[0];
    EXPECT_EQ(l1.height, 13);
    EXPECT_EQ(l1.width, 8);
    EXPECT_EQ(l1.horizontal.height, 6);
    EXPECT_EQ(l1.horizontal.width, 4);
    EXPECT_EQ(l1.vertical.height, 7);
    EXPECT_EQ(l1.vertical.width, 4);
    EXPECT_EQ(l1.diagonal.height, 6);
    EXPECT_EQ(l1.diagonal.width, 4);
    EXPECT_EQ(c.levels[1].height, 7);
    EXPECT_EQ(c.levels[1].width, 4);
    EXPECT_EQ(c.approx.height, 4);
    EXPECT_EQ(c.approx.width, 2);
}

TEST(CpuWavelet, SymmetricLiftingHasDcGainSqrt2AndNoDetailOnConstants) {
    for (const auto& w : kWavelets) {
        const core::LiftingScheme& ls = core::lifting_scheme(w.wavelet);
        for (int n = 2; n <= 23; ++n) {
            const std::vector<double> x(n, 0.625);
            std::vector<double> a((n + 1) / 2), d(n / 2);
            core::dwt_lifting(x, ls, a, d);
            for (double v : a) EXPECT_NEAR(v, 0.625 * std::sqrt(2.0), 1e-14) << w.name << " n=" << n;
            for (double v : d) EXPECT_NEAR(v, 0.0, 1e-14) << w.name << " n=" << n;
        }
    }
}

TEST(CpuWavelet, SymmetricLineOfLengthOnePassesThrough) {
    for (const auto& w : kWavelets) {
        const std::vector<double> x{0.375};
        std::vector<double> a(1), d, y(1);
        core::dwt_lifting(x, core::lifting_scheme(w.wavelet), a, d);
        EXPECT_EQ(a[0], 0.375);
        core::idwt_lifting(a, d, core::lifting_scheme(w.wavelet), y);
        EXPECT_EQ(y[0], 0.375);
    }
}

TEST(CpuWavelet, SymmetricInteriorEqualsPywtFilters) {
    // Far from the borders both modes apply the same filters; db2's lifting is
    // centred on even samples, i.e. pywt's db2 of the line advanced by one
    // sample, with the detail one index later.
    const int n = 64;
    const Plane x = random_plane(1, n + 1, 77);
    for (const auto& w : kWavelets) {
        const bool db2 = w.wavelet == Wavelet::Db2;
        std::vector<double> line(x.data.begin(), x.data.begin() + n), shifted(x.data.begin() + 1, x.data.end());
        std::vector<double> la(n / 2), ld(n / 2), pa(n / 2), pd(n / 2);
        core::dwt_lifting(line, core::lifting_scheme(w.wavelet), la, ld);
        core::dwt_periodization(db2 ? shifted : line, core::filter_bank(w.wavelet), pa, pd);
        // bior4.4: pywt tabulates the 9/7 filters to ~5e-13, the lifting constants are exact.
        const double tol = w.wavelet == Wavelet::Bior44 ? 1e-11 : 1e-13;
        for (int i = 6; i < n / 2 - 6; ++i) {
            EXPECT_NEAR(la[i], pa[i], tol) << w.name << " approx " << i;
            EXPECT_NEAR(ld[i], pd[db2 ? i - 1 : i], tol) << w.name << " detail " << i;
        }
    }
}

}  // namespace
}  // namespace vkfuse

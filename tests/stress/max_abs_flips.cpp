#include "max_abs_flips.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/plane.hpp"
#include "core/rules.hpp"
#include "core/wavelet.hpp"

namespace vkfuse::test {
namespace {

using core::Plane;
using core::WaveletCoeffs;

// A margin float cannot resolve: float32 coefficients carry a rounding of a
// few 1e-7 of the magnitudes that meet in them, which are up to the band's
// largest, not the coefficient itself: 1e-5 of the coefficient plus 1e-6 of
// the band's largest magnitude (over all frames) covers every level with
// room. Swings below kNegligible move no sample by a visible amount.
constexpr double kTieMargin = 1e-5;
constexpr double kBandMargin = 1e-6;
constexpr double kNegligible = 1e-7;

// Every band of a decomposition with the rule that fuses it; the approximation first.
void for_each_band(WaveletCoeffs& c, const FusionSpec& spec, const std::function<void(Plane&, Rule)>& visit) {
    visit(c.approx, spec.base_rule);
    for (auto& level : c.levels) {
        visit(level.horizontal, spec.detail_rule);
        visit(level.vertical, spec.detail_rule);
        visit(level.diagonal, spec.detail_rule);
    }
}

struct NearTie {
    Plane* band;  // in the zeroed copy used to synthesise the effect
    std::size_t at;
    double swing;  // runner-up minus winner
};

// The winner of max-abs at one position is core::combine's; the runner-up is
// the value of largest magnitude among the others.
double runner_up(const std::vector<double>& values, double winner) {
    double best = 0;
    bool skipped = false, any = false;
    for (double v : values) {
        if (!skipped && v == winner) {
            skipped = true;
            continue;
        }
        if (!any || std::abs(v) > std::abs(best)) best = v;
        any = true;
    }
    return best;
}

Plane explain_plane(std::span<const Plane> frames, const FusionSpec& spec, const Plane& gpu, int& near_ties,
                    int& flipped) {
    const int levels = spec.effective_levels();
    std::vector<WaveletCoeffs> all;
    for (const Plane& f : frames) all.push_back(core::wavedec2(f, spec.wavelet, spec.mode, levels));

    // Fuse band by band as the reference does, noting the near-ties in a zeroed twin.
    WaveletCoeffs fused = all[0], impulse = all[0];
    std::vector<std::vector<Plane*>> per_frame(all.size());
    for (std::size_t k = 0; k < all.size(); ++k)
        for_each_band(all[k], spec, [&](Plane& b, Rule) { per_frame[k].push_back(&b); });
    std::vector<NearTie> ties;
    std::size_t band_index = 0;
    std::vector<Plane*> impulse_bands;
    for_each_band(impulse, spec, [&](Plane& b, Rule) {
        std::fill(b.data.begin(), b.data.end(), 0.0);
        impulse_bands.push_back(&b);
    });
    for_each_band(fused, spec, [&](Plane& out, Rule rule) {
        std::vector<double> values(all.size());
        double band_largest = 0;
        for (std::size_t k = 0; k < all.size(); ++k)
            for (double v : per_frame[k][band_index]->data) band_largest = std::max(band_largest, std::abs(v));
        for (std::size_t i = 0; i < out.data.size(); ++i) {
            for (std::size_t k = 0; k < all.size(); ++k) values[k] = per_frame[k][band_index]->data[i];
            out.data[i] = core::combine(rule, values);
            if (rule != Rule::MaxAbs || values.size() < 2) continue;
            const double second = runner_up(values, out.data[i]);
            const double margin = std::abs(out.data[i]) - std::abs(second);
            const double swing = second - out.data[i];
            if (margin <= kTieMargin * std::abs(out.data[i]) + kBandMargin * band_largest &&
                std::abs(swing) > kNegligible)
                ties.push_back({impulse_bands[band_index], i, swing});
        }
        ++band_index;
    });
    near_ties += int(ties.size());

    Plane adjusted = core::waverec2(fused, spec.wavelet, spec.mode);
    adjusted = core::crop(adjusted, gpu.height, gpu.width);
    // Largest swings first: they explain the most, and a small flip judged
    // before a large overlapping one could be kept for the wrong reason.
    std::sort(ties.begin(), ties.end(), [](const NearTie& a, const NearTie& b) {
        return std::abs(a.swing) > std::abs(b.swing);
    });
    for (const NearTie& t : ties) {
        t.band->data[t.at] = t.swing;
        const Plane effect = core::crop(core::waverec2(impulse, spec.wavelet, spec.mode), gpu.height, gpu.width);
        t.band->data[t.at] = 0;
        double before = 0, after = 0;
        for (std::size_t i = 0; i < effect.data.size(); ++i) {
            const double d = gpu.data[i] - adjusted.data[i];
            before += d * d;
            after += (d - effect.data[i]) * (d - effect.data[i]);
        }
        if (after >= before) continue;
        for (std::size_t i = 0; i < effect.data.size(); ++i) adjusted.data[i] += effect.data[i];
        ++flipped;
    }
    return adjusted;
}

}  // namespace

MaxAbsFlips explain_max_abs_flips(std::span<const ImageD> frames, const FusionSpec& spec, const Image& gpu) {
    MaxAbsFlips r;
    r.adjusted = ImageD(gpu.height, gpu.width, gpu.channels);
    const ImageD gpud = convert<double>(gpu);
    std::vector<Plane> planes(frames.size());
    for (int c = 0; c < gpu.channels; ++c) {
        for (std::size_t k = 0; k < frames.size(); ++k) planes[k] = core::extract_channel(frames[k], c);
        const Plane p = explain_plane(planes, spec, core::extract_channel(gpud, c), r.near_ties, r.flipped);
        core::insert_channel(p, r.adjusted, c);
    }
    return r;
}

}  // namespace vkfuse::test

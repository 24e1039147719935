// Wavelet fusion: decompose every frame, fuse the approximation with the base
// rule and every detail band with the detail rule, invert (docs/spec.md).
#include <vector>

#include "core/fusion_methods.hpp"
#include "core/rules.hpp"
#include "core/wavelet.hpp"

namespace vkfuse::core {
namespace {

// The same band of every frame (pick selects it), fused with one rule.
template <class Pick>
Plane fuse_band(Rule rule, const std::vector<WaveletCoeffs>& all, Pick pick) {
    std::vector<const Plane*> band;
    for (const WaveletCoeffs& c : all) band.push_back(&pick(c));
    return combine_planes(rule, band);
}

}  // namespace

Plane fuse_wavelet(std::span<const Plane> frames, const FusionSpec& spec) {
    const int levels = spec.effective_levels();
    std::vector<WaveletCoeffs> all;
    for (const Plane& f : frames) all.push_back(wavedec2(f, spec.wavelet, spec.mode, levels));

    WaveletCoeffs fused;
    fused.approx = fuse_band(spec.base_rule, all, [](const WaveletCoeffs& c) -> const Plane& { return c.approx; });
    for (int l = 0; l < levels; ++l) {
        WaveletLevel out{all[0].levels[l].height, all[0].levels[l].width, {}, {}, {}};
        out.horizontal = fuse_band(spec.detail_rule, all,
                                   [l](const WaveletCoeffs& c) -> const Plane& { return c.levels[l].horizontal; });
        out.vertical = fuse_band(spec.detail_rule, all,
                                 [l](const WaveletCoeffs& c) -> const Plane& { return c.levels[l].vertical; });
        out.diagonal = fuse_band(spec.detail_rule, all,
                                 [l](const WaveletCoeffs& c) -> const Plane& { return c.levels[l].diagonal; });
        fused.levels.push_back(std::move(out));
    }
    return waverec2(fused, spec.wavelet, spec.mode);
}

ImageD fuse_wavelet(std::span<const ImageD> frames, const FusionSpec& spec) {
    return per_channel(frames, [&](std::span<const Plane> p) { return fuse_wavelet(p, spec); });
}

}  // namespace vkfuse::core

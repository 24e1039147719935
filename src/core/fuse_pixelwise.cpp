// The per-pixel methods: channel-sum, Brovey and the mean (docs/spec.md, "Fusion methods").
#include <vector>

#include "core/compensated_sum.hpp"
#include "core/fusion_methods.hpp"

namespace vkfuse::core {
namespace {

// Brovey at one pixel and channel: p_k = max(I_k, 0), s = sum p_k;
// sum (p_k / s) I_k when s >= 1e-6, else the plain mean (a dark pixel in every
// frame has no meaningful ratio).
double brovey(const std::vector<double>& v) {
    double s = 0, mean = 0;
    for (double x : v) {
        s += x > 0 ? x : 0.0;
        mean += x;
    }
    if (s < 1e-6) return mean / double(v.size());
    double out = 0;
    for (double x : v) out += ((x > 0 ? x : 0.0) / s) * x;
    return out;
}

}  // namespace

ImageD fuse_channel_sum(std::span<const ImageD> frames, const FusionSpec&) {
    // Frame k was lit by LED k alone (red, green, blue), so its own channel k
    // is the only one carrying that light.
    const ImageD& f0 = frames[0];
    ImageD out(f0.height, f0.width, 3);
    for (int y = 0; y < f0.height; ++y)
        for (int x = 0; x < f0.width; ++x)
            for (int c = 0; c < 3; ++c) out.at(y, x, c) = frames[c].at(y, x, c);
    return out;
}

ImageD fuse_brovey(std::span<const ImageD> frames, const FusionSpec&) {
    const ImageD& f0 = frames[0];
    ImageD out(f0.height, f0.width, f0.channels);
    std::vector<double> v(frames.size());
    for (std::size_t i = 0; i < out.data.size(); ++i) {
        for (std::size_t k = 0; k < frames.size(); ++k) v[k] = frames[k].data[i];
        out.data[i] = brovey(v);
    }
    return out;
}

ImageD fuse_mean(std::span<const ImageD> frames) {
    ImageD out(frames[0].height, frames[0].width, frames[0].channels);
    for (std::size_t i = 0; i < out.data.size(); ++i) {
        CompensatedSum sum;
        for (const ImageD& f : frames) sum.add(f.data[i]);
        out.data[i] = sum.value() / double(frames.size());
    }
    return out;
}

}  // namespace vkfuse::core

// Laplacian-pyramid fusion with OpenCV-exact pyrDown/pyrUp (docs/spec.md).
#include <vector>

#include "core/fusion_methods.hpp"
#include "core/pyramid.hpp"
#include "core/rules.hpp"

namespace vkfuse::core {
namespace {

Plane subtract(const Plane& a, const Plane& b) {
    Plane out(a.height, a.width);
    for (std::size_t i = 0; i < out.data.size(); ++i) out.data[i] = a.data[i] - b.data[i];
    return out;
}

Plane add(const Plane& a, const Plane& b) {
    Plane out(a.height, a.width);
    for (std::size_t i = 0; i < out.data.size(); ++i) out.data[i] = a.data[i] + b.data[i];
    return out;
}

// Lap_0 .. Lap_L of one frame: G_0 = I, G_{l+1} = pyrDown(G_l),
// Lap_l = G_l - pyrUp(G_{l+1}, size of G_l), Lap_L = G_L.
std::vector<Plane> laplacian_pyramid(const Plane& image, int levels) {
    std::vector<Plane> lap;
    Plane g = image;
    for (int l = 0; l < levels; ++l) {
        Plane next = pyr_down(g);
        lap.push_back(subtract(g, pyr_up(next, g.height, g.width)));
        g = std::move(next);
    }
    lap.push_back(std::move(g));
    return lap;
}

}  // namespace

Plane fuse_laplacian(std::span<const Plane> frames, int levels, Rule base, Rule detail) {
    std::vector<std::vector<Plane>> pyramids;
    for (const Plane& f : frames) pyramids.push_back(laplacian_pyramid(f, levels));

    std::vector<Plane> fused;  // C_0 .. C_L
    std::vector<const Plane*> level(frames.size());
    for (int l = 0; l <= levels; ++l) {
        for (std::size_t k = 0; k < frames.size(); ++k) level[k] = &pyramids[k][l];
        fused.push_back(combine_planes(l < levels ? detail : base, level));
    }

    // Collapse: R_L = C_L, R_l = pyrUp(R_{l+1}, size of C_l) + C_l.
    Plane r = fused[levels];
    for (int l = levels - 1; l >= 0; --l) r = add(pyr_up(r, fused[l].height, fused[l].width), fused[l]);
    return r;
}

ImageD fuse_laplacian(std::span<const ImageD> frames, const FusionSpec& spec) {
    return per_channel(frames, [&](std::span<const Plane> p) {
        return fuse_laplacian(p, spec.effective_levels(), spec.base_rule, spec.detail_rule);
    });
}

}  // namespace vkfuse::core

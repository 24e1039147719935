// The elastomer's response to a pressed object (sim/gel.hpp).
#include "sim/gel.hpp"

#include <algorithm>
#include <cmath>

namespace vkfuse::sim {
namespace {

// How far the indentation spreads beyond the contact: of the order of the gel
// thickness (DIGIT: about 2-3 mm of silicone), a Gaussian of this sigma.
constexpr double kSkirtSigmaMm = 0.7;
// Bending stiffness of the coated membrane: it cannot follow steps sharper
// than this, so relief keeps its shape but loses its corners.
constexpr double kMembraneSigmaMm = 0.05;

void compute_normals(GelSurface& s, const Grid& grid) {
    const Raster& h = s.height;
    const double inv = 1.0 / (2.0 * grid.mm_per_px);
    for (int y = 0; y < h.height; ++y)
        for (int x = 0; x < h.width; ++x) {
            // One-sided at the border via clamping: half the central slope there, harmless.
            const double gx = (h.at(y, std::min(x + 1, h.width - 1)) - h.at(y, std::max(x - 1, 0))) * inv;
            const double gy = (h.at(std::min(y + 1, h.height - 1), x) - h.at(std::max(y - 1, 0), x)) * inv;
            const double norm = 1.0 / std::sqrt(gx * gx + gy * gy + 1.0);
            s.nx.at(y, x) = float(-gx * norm);
            s.ny.at(y, x) = float(-gy * norm);
            s.nz.at(y, x) = float(norm);
        }
}

}  // namespace

GelSurface flat_gel(const Grid& grid) {
    return {Raster(grid), Raster(grid), Raster(grid), Raster(grid, 1.0f), 0.0f};
}

GelSurface press_gel(const Raster& relief, double depth_mm, const Grid& grid) {
    Raster contact(grid);
    for (std::size_t i = 0; i < contact.v.size(); ++i) contact.v[i] = std::max(0.0f, float(relief.v[i] + depth_mm));
    Raster skirt = contact;
    gaussian_blur(skirt, kSkirtSigmaMm / grid.mm_per_px);
    GelSurface s = flat_gel(grid);
    // Where the object touches, the membrane lies on it; elsewhere it hangs
    // from the contact like the skirt. Narrow valleys between touching parts
    // fill up to the skirt, as a soft layer does not reach into fine grooves.
    for (std::size_t i = 0; i < contact.v.size(); ++i) s.height.v[i] = std::max(contact.v[i], skirt.v[i]);
    gaussian_blur(s.height, kMembraneSigmaMm / grid.mm_per_px);
    s.max_height = *std::max_element(s.height.v.begin(), s.height.v.end());
    compute_normals(s, grid);
    return s;
}

}  // namespace vkfuse::sim

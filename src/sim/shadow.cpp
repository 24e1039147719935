// Shadows cast on the membrane by its own relief (sim/optics.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/optics.hpp"

namespace vkfuse::sim {
namespace {

// Membrane height at a point in mm (bilinear); the flat rest plane outside the
// field of view, where nothing is pressed that we know of.
double height_at(const GelSurface& s, const Grid& g, double x_mm, double y_mm) {
    const double fx = x_mm / g.mm_per_px + 0.5 * g.width - 0.5;
    const double fy = y_mm / g.mm_per_px + 0.5 * g.height - 0.5;
    if (fx < 0 || fy < 0 || fx > g.width - 1 || fy > g.height - 1) return 0;
    const int x0 = std::min(int(fx), g.width - 2), y0 = std::min(int(fy), g.height - 2);
    const double ax = fx - x0, ay = fy - y0;
    const Raster& h = s.height;
    return (1 - ay) * ((1 - ax) * h.at(y0, x0) + ax * h.at(y0, x0 + 1)) +
           ay * ((1 - ax) * h.at(y0 + 1, x0) + ax * h.at(y0 + 1, x0 + 1));
}

// tan of the horizon seen from (row, col) toward the LED: the steepest rise of
// the membrane along that direction. Stops once nothing further (nothing is
// higher than `highest`) can rise above `floor_tan` (the lowest ray of the
// band) or the horizon so far.
double horizon_tan(const GelSurface& s, const Grid& g, int row, int col, const LightDirection& towards, double floor_tan,
                   double highest) {
    const double px = g.x_mm(col), py = g.y_mm(row), pz = s.height.at(row, col);
    const auto l = towards.at(px, py);
    const double planar = std::hypot(l[0], l[1]);
    const double ux = l[0] / planar, uy = l[1] / planar;
    double best = floor_tan;
    // Steps of a pixel near the point, growing with distance: a far occluder
    // needs less spatial precision for the same angular precision.
    for (double t = g.mm_per_px; highest - pz > best * t; t += std::max(g.mm_per_px, 0.05 * t)) {
        const double qx = px + ux * t, qy = py + uy * t;
        if (std::abs(qx) > 0.5 * Grid::kFieldWidthMm || std::abs(qy) > 0.5 * Grid::kFieldHeightMm) break;
        best = std::max(best, (height_at(s, g, qx, qy) - pz) / t);
    }
    return best;
}

}  // namespace

Raster led_visibility(const GelSurface& surface, const Grid& grid, const LedRig& rig, int led) {
    Raster vis(grid, 1.0f);
    if (surface.max_height <= 0) return vis;  // a flat membrane shadows nothing
    const double deg = std::numbers::pi / 180.0;
    const double lo = rig.elevation_min_deg * deg, hi = rig.elevation_max_deg * deg;
    const double floor_tan = std::tan(lo);
    const LightDirection towards(rig, led);
    // Only what rises above a point can shadow it, and only within the reach
    // of the lowest ray: points with nothing higher around are lit.
    Raster around = surface.height;
    max_filter(around, int(std::ceil(surface.max_height / floor_tan / grid.mm_per_px)));
    for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x < grid.width; ++x) {
            if (around.at(y, x) <= surface.height.at(y, x)) continue;
            // The rays of the band below the horizon are blocked, those above arrive.
            const double horizon = std::atan(horizon_tan(surface, grid, y, x, towards, floor_tan, around.at(y, x)));
            vis.at(y, x) = float(std::clamp((hi - horizon) / (hi - lo), 0.0, 1.0));
        }
    return vis;
}

}  // namespace vkfuse::sim

// Shading of the membrane under each LED (sim/optics.hpp).
#include "sim/optics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vkfuse::sim {
namespace {

using Vec = std::array<double, 3>;
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec unit(const Vec& a) {
    const double n = std::sqrt(dot(a, a));
    return {a[0] / n, a[1] / n, a[2] / n};
}

// cos^exponent for lobes; tiny cosines give 0 outright, since pow() on values
// that underflow to subnormals is a hundred times slower and adds nothing.
double lobe(double cosine, double exponent) { return cosine > 1e-4 ? std::pow(cosine, exponent) : 0.0; }

// Lambert plus Blinn-Phong for normal n, light l, view v.
double reflect(const LedRig& rig, const Vec& n, const Vec& l, const Vec& v) {
    const Vec h = unit({l[0] + v[0], l[1] + v[1], l[2] + v[2]});
    return std::max(0.0, dot(n, l)) * (1.0 + rig.specular * lobe(dot(n, h), rig.shininess));
}

// How much brighter (or darker) a patch with normal n and LED visibility vis
// is than the flat membrane at the same place.
double relative_shading(const LedRig& rig, const Vec& n, const Vec& l, const Vec& v, double vis) {
    const double flat = reflect(rig, {0, 0, 1}, l, v);
    const double f = rig.diffuse_fraction;
    return (1 - f) * vis * reflect(rig, n, l, v) / flat + f * 0.5 * (1 + n[2]);
}

}  // namespace

LightDirection::LightDirection(const LedRig& rig, int led) {
    const double az = rig.leds[std::size_t(led)].azimuth_deg * std::numbers::pi / 180.0;
    const double el = 0.5 * (rig.elevation_min_deg + rig.elevation_max_deg) * std::numbers::pi / 180.0;
    rim_x_ = rig.rim_mm * std::cos(az);
    rim_y_ = rig.rim_mm * std::sin(az);
    cos_el_ = std::cos(el);
    sin_el_ = std::sin(el);
}

LedImages render_led_images(const GelSurface& surface, const Grid& grid, const LedRig& rig) {
    LedImages images;
    for (int k = 0; k < 3; ++k) {
        const Led& led = rig.leds[std::size_t(k)];
        const LightDirection towards(rig, k);
        const Raster vis = led_visibility(surface, grid, rig, k);
        std::vector<float>& out = images[std::size_t(k)];
        out.assign(grid.size() * 3, 0.0f);
        for (int y = 0; y < grid.height; ++y)
            for (int x = 0; x < grid.width; ++x) {
                const double px = grid.x_mm(x), py = grid.y_mm(y), pz = surface.height.at(y, x);
                const Vec n{surface.nx.at(y, x), surface.ny.at(y, x), surface.nz.at(y, x)};
                const double flat = std::max(0.0, evaluate(led.field, px, py));
                // Untouched and unshadowed: exactly the calibrated light, no shading to compute.
                const bool plain = n[2] == 1.0 && vis.at(y, x) == 1.0f;
                const double light =
                    plain ? flat
                          : flat * relative_shading(rig, n, towards.at(px, py), unit({-px, -py, rig.camera_mm - pz}),
                                                    vis.at(y, x));
                float* px_out = &out[(std::size_t(y) * grid.width + x) * 3];
                for (int c = 0; c < 3; ++c) px_out[c] = float(rig.crosstalk[std::size_t(c)][std::size_t(k)] * light);
            }
    }
    return images;
}

}  // namespace vkfuse::sim

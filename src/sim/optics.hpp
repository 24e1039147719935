// sim/optics.hpp - what the camera sees of the membrane under each LED.
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "sim/gel.hpp"
#include "sim/led.hpp"
#include "sim/raster.hpp"

namespace vkfuse::sim {

// Per LED: the camera's linear response (DN, HWC with 3 channels) to that LED
// alone at full drive. Light adds linearly, so any LED setting, or a mix of
// settings over a row's exposure, is a weighted sum of these three images;
// that is why they are computed once per pressed object and not per frame.
using LedImages = std::array<std::vector<float>, 3>;

// Shading model. The calibrated light field gives what a flat membrane
// reflects; a tilted or shadowed patch reflects that times
//   (1 - f) * visible * D(n) / D(flat) + f * (1 + n_z) / 2,
// D(n) = max(0, n.l) * (1 + specular * max(0, n.h)^shininess)  (Lambert + Blinn-Phong),
// with l the grazing direction to the LED, h the half vector toward the
// camera, f the diffuse fraction (sky-like light of a hemisphere).
LedImages render_led_images(const GelSurface& surface, const Grid& grid, const LedRig& rig);

// Fraction of the LED's band of elevations visible from each membrane point
// (1 lit, 0 in full shadow): the horizon toward the LED over the height field
// hides the rays below it. Grazing light makes even shallow relief cast shadows.
Raster led_visibility(const GelSurface& surface, const Grid& grid, const LedRig& rig, int led);

// Unit vectors from membrane points toward one LED of the rig: the rim
// direction in the plane, raised to the middle of the rig's elevation band.
class LightDirection {
public:
    LightDirection(const LedRig& rig, int led);
    std::array<double, 3> at(double x_mm, double y_mm) const {
        const double dx = rim_x_ - x_mm, dy = rim_y_ - y_mm;
        const double inv = cos_el_ / std::sqrt(dx * dx + dy * dy);
        return {dx * inv, dy * inv, sin_el_};
    }

private:
    double rim_x_, rim_y_, cos_el_, sin_el_;
};

}  // namespace vkfuse::sim

// sim/lighting.hpp - the light on the gel: the DIGIT's three rim LEDs, the
// membrane's shading and shadows under each, and a contact rendered as the
// image each LED alone would give.
#pragma once
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "sim/gel.hpp"
#include "sim/raster.hpp"

namespace vkfuse::sim {

// The DIGIT's three rim LEDs and its camera's colour response, as numbers
// calibrated against a real DIGIT background frame.

// The light one LED puts on the flat, untouched gel as the camera sees it
// (lens shading included), in camera DN at full drive: a cubic polynomial in
// (x, y) / 10 mm with terms 1, x, y, x^2, xy, y^2, x^3, x^2 y, x y^2, y^3.
// How the housing and light guide spread an LED's light is not modelled from
// first principles; it is measured (see sim/calibration.hpp).
using LightField = std::array<double, 10>;
// The ten terms at a point (what the coefficients multiply).
LightField light_field_terms(double x_mm, double y_mm);
double evaluate(const LightField& field, double x_mm, double y_mm);

// crosstalk[c][k]: response of camera channel c to LED k relative to LED k's
// own channel. The LEDs' spectra overlap the neighbouring colour filters.
using Crosstalk = std::array<std::array<double, 3>, 3>;

struct Led {
    double azimuth_deg = 0;  // where on the rim it sits, from +x toward +y (down)
    LightField field{};
};

// The gel's coordinates: x right, y down (mm from the centre of the field of
// view), z from the membrane's rest plane toward the camera.
struct LedRig {
    std::array<Led, 3> leds;  // red, green, blue: the DIGIT's LED channels r, g, b
    Crosstalk crosstalk{};
    double rim_mm = 14;            // LEDs' distance from the centre, beyond the field's corners
    // Grazing light: it arrives between these elevations above the gel's
    // plane. The LEDs shine through the acrylic window, which spreads them
    // into a band of angles, so shadows are soft and partial.
    double elevation_min_deg = 10;
    double elevation_max_deg = 35;
    double diffuse_fraction = 0.2; // light scattered by gel and housing, arriving from all directions
    double specular = 0.4;         // Blinn-Phong weight of the membrane's coating, relative to Lambert
    double shininess = 12;         // Blinn-Phong exponent: a satin coating
    double camera_mm = 10;         // lens height above the membrane (view directions)
};

// The rig fitted to tests/data/digit_bg_tacto.png (see digit_led_rig in sim/lighting.cpp).
LedRig digit_led_rig();

// A DIGIT LED level 0..max_level as a fraction of full light: linear in the
// level, as a PWM- or current-DAC-driven LED is.
inline double led_drive(int level, int max_level) { return double(level) / double(max_level); }

// What the camera sees of the membrane under each LED.

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

// An object pressed into the gel, as the camera sees it under each LED:
// everything about a frame that does not change per frame.

struct Contact {
    std::string object = "nothing";  // a name make_relief knows
    double depth_mm = 0;
    double x = 0.5, y = 0.5;         // centre, fractions of the field

    bool operator==(const Contact&) const = default;
};

// The per-LED camera images of the gel with contact pressed in.
LedImages render_scene(const Contact& contact, const Grid& grid, const LedRig& rig);

}  // namespace vkfuse::sim

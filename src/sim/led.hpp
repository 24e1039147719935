// sim/led.hpp - the DIGIT's three rim LEDs and its camera's colour
// response, as numbers calibrated against a real DIGIT background frame.
#pragma once
#include <array>

namespace vkfuse::sim {

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

// The rig fitted to tests/data/digit_bg_tacto.png (see sim/led.cpp).
LedRig digit_led_rig();

// A DIGIT LED level 0..max_level as a fraction of full light: linear in the
// level, as a PWM- or current-DAC-driven LED is.
inline double led_drive(int level, int max_level) { return double(level) / double(max_level); }

}  // namespace vkfuse::sim

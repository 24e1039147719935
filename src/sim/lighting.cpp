// The light on the gel (sim/lighting.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sim/gel.hpp"
#include "sim/lighting.hpp"
#include "sim/relief.hpp"

namespace vkfuse::sim {

LightField light_field_terms(double x_mm, double y_mm) {
    const double x = x_mm / 10, y = y_mm / 10;
    return {1, x, y, x * x, x * y, y * y, x * x * x, x * x * y, x * y * y, y * y * y};
}

double evaluate(const LightField& field, double x_mm, double y_mm) {
    const LightField t = light_field_terms(x_mm, y_mm);
    double sum = 0;
    for (std::size_t j = 0; j < t.size(); ++j) sum += field[j] * t[j];
    return sum;
}

LedRig digit_led_rig() {
    LedRig rig;
    // Red (about 625 nm) and blue (465 nm) LEDs leak little into the other
    // filters; green (525 nm) sits between and leaks into both, most into blue.
    rig.crosstalk = {{{1.0, 0.10, 0.05}, {0.08, 1.0, 0.20}, {0.02, 0.25, 1.0}}};
    // Rim positions: a light-guide model (beam lobe times exp(-distance /
    // length), free position, lobe and length per LED) fitted to the same
    // frame puts the red LED at 294, green at 57 and blue at 190 degrees, close
    // to the 120 degrees apart they are mounted at.
    // Fields: fit_light_fields(landscape_from_portrait(digit_bg_tacto.png),
    // crosstalk above); tests/test_cpu_sim_calibration.cpp re-derives them.
    rig.leds[0] = {294, {117.527, 88.2802, -115.976, -52.3003, -9.92172, -69.1813, -74.839, 72.685, -67.9473, 81.8837}};
    rig.leds[1] = {57, {95.3221, 28.0137, 55.1348, -24.2782, -7.33405, -22.7366, -24.6492, -37.7113, -4.01214, -36.0038}};
    rig.leds[2] = {190, {80.0267, -21.8651, -57.9609, 9.05021, 13.7736, -36.2231, 60.9443, 41.1814, 21.2825, 38.2553}};
    return rig;
}

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

LedImages render_scene(const Contact& contact, const Grid& grid, const LedRig& rig) {
    const auto relief = make_relief(contact.object);
    if (!relief) throw std::logic_error("render_scene: unknown object " + contact.object);  // validated by the caller
    const double cx = (contact.x - 0.5) * Grid::kFieldWidthMm;
    const double cy = (contact.y - 0.5) * Grid::kFieldHeightMm;
    const GelSurface gel = press_gel(sample_relief(*relief, grid, cx, cy), contact.depth_mm, grid);
    return render_led_images(gel, grid, rig);
}

}  // namespace vkfuse::sim

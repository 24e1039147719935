#include "inputs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace vkfuse::bench {

Inputs::Inputs(Size size, int frames, int sensors)
    : size_(size), frames_(frames), sensors_(sensors), scenes_(std::min(sensors, kMaxScenes)) {
    for (int i = 0; i < scenes_; ++i) {
        const TactileScene scene = make_scene(i);
        for (int k = 0; k < frames; ++k) images_.push_back(tactile_frame(size, scene, k, frames));
        backgrounds_.push_back(tactile_background(size, scene, frames));
    }
}

std::vector<FrameView> Inputs::views() const {
    std::vector<FrameView> out;
    for (int s = 0; s < sensors_; ++s)
        for (int k = 0; k < frames_; ++k) out.push_back(FrameView::of(frame(s, k)));
    return out;
}

namespace {

// splitmix64: a stateless hash, so any pixel's noise is known without a stream.
std::uint64_t mix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

double unit(std::uint64_t h) { return double(h >> 11) * 0x1.0p-53; }

// Roughly Gaussian (Irwin-Hall of four uniforms), unit variance.
double gaussish(std::uint64_t key) {
    double s = 0;
    for (int i = 0; i < 4; ++i) s += unit(mix(key + std::uint64_t(i) * 0x632be59bd9b4e019ull));
    return (s - 2.0) * std::sqrt(3.0);
}

// DIGIT's LEDs are red, green and blue; more LEDs reuse mixed colours.
std::array<double, 3> led_colour(int led) {
    static constexpr std::array<std::array<double, 3>, 5> kColours{
        {{0.95, 0.22, 0.18}, {0.20, 0.92, 0.26}, {0.22, 0.24, 0.95}, {0.80, 0.72, 0.20}, {0.25, 0.75, 0.80}}};
    return kColours[std::size_t(led) % kColours.size()];
}

struct Surface {
    double nx = 0, ny = 0, nz = 1;  // unit normal of the gel surface
};

// The pressed object: a spherical cap with ridges, as its height's gradient.
Surface surface_at(const TactileScene& s, double px, double py) {
    const double dx = px - s.cx, dy = py - s.cy;
    const double r2 = (dx * dx + dy * dy) / (s.radius * s.radius);
    if (r2 >= 1.0) return {};
    const double ca = std::cos(s.ridge_angle), sa = std::sin(s.ridge_angle);
    const double phase = s.ridges * (px * ca + py * sa);
    const double texture = 1.0 + 0.15 * std::sin(phase), dtexture = 0.15 * std::cos(phase) * s.ridges;
    const double cap = s.depth * (1.0 - r2);
    const double dcap = -2.0 * s.depth / (s.radius * s.radius);
    const double hx = dcap * dx * texture + cap * dtexture * ca;
    const double hy = dcap * dy * texture + cap * dtexture * sa;
    const double n = std::sqrt(hx * hx + hy * hy + 1.0);
    return {-hx / n, -hy / n, 1.0 / n};
}

// Light of one LED at the gel point (px, py): a direction of incidence and a
// falloff with distance from the LED at the gel's rim.
struct Light {
    double lx, ly, lz;
    double x, y;  // LED position, image heights from the centre
};

Light led_light(int led, int leds, double aspect) {
    const double theta = 2.0 * std::numbers::pi * led / leds + 0.3;
    const double phi = std::numbers::pi / 3;
    return {std::cos(theta) * std::sin(phi), std::sin(theta) * std::sin(phi), std::cos(phi), 0.55 * aspect * std::cos(theta),
            0.55 * std::sin(theta)};
}

double shade(const Light& l, const Surface& n, double px, double py) {
    const double d2 = (px - l.x) * (px - l.x) + (py - l.y) * (py - l.y);
    const double falloff = 1.0 / (1.0 + 2.5 * d2);
    return std::max(0.0, n.nx * l.lx + n.ny * l.ly + n.nz * l.lz) * falloff;
}

template <class PixelFn>
Image render(Size size, PixelFn pixel) {
    Image img(size.height, size.width, 3);
    const double inv_h = 1.0 / size.height;
    for (int y = 0; y < size.height; ++y) {
        const double py = (y + 0.5 - 0.5 * size.height) * inv_h;
        for (int x = 0; x < size.width; ++x) {
            const double px = (x + 0.5 - 0.5 * size.width) * inv_h;
            const std::array<double, 3> rgb = pixel(x, y, px, py);
            for (int c = 0; c < 3; ++c) img.at(y, x, c) = float(std::clamp(rgb[std::size_t(c)], 0.0, 1.0));
        }
    }
    return img;
}

double vignette(double px, double py) { return 1.0 - 0.35 * (px * px + py * py); }

}  // namespace

TactileScene make_scene(int scene) {
    const std::uint64_t h = mix(std::uint64_t(scene) * 0x2545f4914f6cdd1dull + 17);
    TactileScene s;
    s.cx = 0.5 * (unit(mix(h + 1)) - 0.5);
    s.cy = 0.4 * (unit(mix(h + 2)) - 0.5);
    s.radius = 0.12 + 0.15 * unit(mix(h + 3));
    s.depth = 0.03 + 0.05 * unit(mix(h + 4));
    s.ridges = 30.0 + 60.0 * unit(mix(h + 5));
    s.ridge_angle = std::numbers::pi * unit(mix(h + 6));
    s.gain = 0.92 + 0.16 * unit(mix(h + 7));
    s.seed = mix(h + 8);
    return s;
}

Image tactile_frame(Size size, const TactileScene& scene, int led, int leds) {
    const Light light = led_light(led, leds, double(size.width) / size.height);
    const auto colour = led_colour(led);
    const std::uint64_t noise_key = mix(scene.seed + std::uint64_t(led) * 0x9e3779b97f4a7c15ull);
    return render(size, [&](int x, int y, double px, double py) {
        const double lit = 1.7 * scene.gain * shade(light, surface_at(scene, px, py), px, py) * vignette(px, py);
        std::array<double, 3> rgb{};
        for (int c = 0; c < 3; ++c) {
            const std::uint64_t key = noise_key ^ ((std::uint64_t(y) << 34) | (std::uint64_t(x) << 2) | std::uint64_t(c));
            rgb[std::size_t(c)] = 0.06 + 0.02 * c + colour[std::size_t(c)] * lit + 0.008 * gaussish(mix(key));
        }
        return rgb;
    });
}

Image tactile_background(Size size, const TactileScene& scene, int leds) {
    std::vector<Light> lights;
    for (int k = 0; k < leds; ++k) lights.push_back(led_light(k, leds, double(size.width) / size.height));
    return render(size, [&](int, int, double px, double py) {
        std::array<double, 3> rgb{};
        for (int k = 0; k < leds; ++k) {
            const double lit = 1.7 * scene.gain * shade(lights[std::size_t(k)], Surface{}, px, py) * vignette(px, py) / leds;
            const auto colour = led_colour(k);
            for (int c = 0; c < 3; ++c) rgb[std::size_t(c)] += colour[std::size_t(c)] * lit;
        }
        for (int c = 0; c < 3; ++c) rgb[std::size_t(c)] += 0.06 + 0.02 * c;
        return rgb;
    });
}

}  // namespace vkfuse::bench

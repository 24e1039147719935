// Objects whose face is a fine periodic texture (sim/relief.hpp): a
// screw's thread, the hooks of velcro, the teeth of a file.
#include <cmath>
#include <numbers>

#include "sim/relief.hpp"
#include "sim/shapes.hpp"

namespace vkfuse::sim {
namespace {

// Fractional part in [0, 1).
double frac(double x) { return x - std::floor(x); }

// An M5 screw lying along u: 60-degree thread of pitch 0.8 mm, depth 0.45 mm,
// crests slightly flattened; the helix tilts the crests by its lead angle.
class Screw final : public Relief {
public:
    double height(double u, double v) const override {
        const double lead = std::atan(kPitch / (std::numbers::pi * 2 * kMajor));
        const double phase = frac((u + v * std::tan(lead)) / kPitch);
        const double tri = std::min(1.0, 2.4 * std::min(phase, 1.0 - phase));  // 0 root .. 1 crest
        const double radius = kMajor - kDepth * (1.0 - tri);
        if (std::abs(v) >= radius) return kAbsent;
        return std::sqrt(radius * radius - v * v) - kMajor;
    }

private:
    static constexpr double kMajor = 2.5, kPitch = 0.8, kDepth = 0.45;
};

// Velcro, hook side: hooks about 0.5 mm across, 0.4 mm tall, on a jittered
// 0.9 mm grid, on a tape 16 x 11 mm.
class Velcro final : public Relief {
public:
    double height(double u, double v) const override {
        if (std::abs(u) > 8.0 || std::abs(v) > 5.5) return kAbsent;
        const int ci = int(std::floor(u / kPitch)), cj = int(std::floor(v / kPitch));
        double top = 0;
        for (int i = ci - 1; i <= ci + 1; ++i)
            for (int j = cj - 1; j <= cj + 1; ++j) {
                const double hu = (i + 0.5 + 0.45 * (cell_hash(i, j, 1) - 0.5)) * kPitch;
                const double hv = (j + 0.5 + 0.45 * (cell_hash(i, j, 2) - 0.5)) * kPitch;
                const double d = std::hypot(u - hu, v - hv) / kHook;
                if (d < 1) top = std::max(top, std::sqrt(1.0 - d * d));  // a dome of the hook's bend
            }
        return kHeight * (top - 1.0);
    }

private:
    static constexpr double kPitch = 0.9, kHook = 0.27, kHeight = 0.4;
};

// A double-cut file: two sets of sawtooth cuts (0.6 mm pitch at +65 degrees,
// 0.75 mm at -45 degrees) leave diamond teeth 0.15 mm tall on a 9 mm blade.
class File final : public Relief {
public:
    double height(double u, double v) const override {
        if (std::abs(v) > kHalfWidth) return kAbsent;
        const double a = 65.0 * std::numbers::pi / 180.0, b = -45.0 * std::numbers::pi / 180.0;
        const double s1 = saw((u * std::cos(a) + v * std::sin(a)) / 0.6);
        const double s2 = saw((u * std::cos(b) + v * std::sin(b)) / 0.75);
        const double edge = std::abs(v) > kHalfWidth - kRound
                                ? kRound - std::sqrt(std::max(0.0, kRound * kRound - std::pow(std::abs(v) - kHalfWidth + kRound, 2)))
                                : 0.0;
        return kTooth * (std::min(s1, s2) - 1.0) - edge;
    }

private:
    // A cut's profile: a long flank rising to the tooth's edge, a short steep one falling.
    static double saw(double x) {
        const double p = frac(x);
        return p < 0.8 ? p / 0.8 : (1.0 - p) / 0.2;
    }
    static constexpr double kHalfWidth = 4.5, kRound = 0.5, kTooth = 0.15;
};

}  // namespace

std::unique_ptr<Relief> make_screw() { return std::make_unique<Screw>(); }
std::unique_ptr<Relief> make_velcro() { return std::make_unique<Velcro>(); }
std::unique_ptr<Relief> make_file() { return std::make_unique<File>(); }

}  // namespace vkfuse::sim

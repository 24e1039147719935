// Solid objects with plain faces (sim/relief.hpp): a ball, the top of a
// 2x2 LEGO brick with its studs, and a hex nut. Standard dimensions in mm.
#include <cmath>
#include <vector>

#include "sim/glyphs.hpp"
#include "sim/relief.hpp"
#include "sim/shapes.hpp"

namespace vkfuse::sim {
namespace {

// A 10 mm ball.
class Ball final : public Relief {
public:
    double height(double u, double v) const override {
        const double r2 = u * u + v * v;
        return r2 >= kR * kR ? kAbsent : std::sqrt(kR * kR - r2) - kR;
    }

private:
    static constexpr double kR = 5.0;
};

// LEGO: studs 4.8 mm across, 1.7 mm tall, 8 mm apart, edges rounded, each
// with the raised logo the moulds leave on top (about 0.1 mm).
class Lego final : public Relief {
public:
    Lego() {
        std::vector<Polyline> logos;
        for (double su : {-4.0, 4.0})
            for (double sv : {-4.0, 4.0}) {
                auto logo = text_strokes("LEGO", 0.9, {su, sv});
                logos.insert(logos.end(), logo.begin(), logo.end());
            }
        logo_ = Strokes(std::move(logos));
    }

    double height(double u, double v) const override {
        if (std::abs(u) > kHalfBrick || std::abs(v) > kHalfBrick) return kAbsent;
        const double su = u - (u < 0 ? -4.0 : 4.0), sv = v - (v < 0 ? -4.0 : 4.0);
        const double r = std::hypot(su, sv);
        if (r >= kStudR) return -kStudH - kLogo;
        const double edge = r > kStudR - kRound ? kRound - std::sqrt(std::max(0.0, kRound * kRound -
                                                      (r - kStudR + kRound) * (r - kStudR + kRound)))
                                                : 0.0;
        const double logo = ridge(logo_.distance({u, v}, kLogoStroke), kLogoStroke) * kLogo;
        return -kLogo - edge + logo;
    }

private:
    static constexpr double kHalfBrick = 7.8, kStudR = 2.4, kStudH = 1.7, kRound = 0.25, kLogo = 0.1, kLogoStroke = 0.1;
    Strokes logo_;
};

// An M5 nut lying flat: 8 mm across flats, 5 mm hole; the 30-degree chamfer
// cuts the corners off the face, the hole is countersunk 0.3 mm.
class Nut final : public Relief {
public:
    double height(double u, double v) const override {
        const double r = std::hypot(u, v);
        if (hexagon_sdf(u, v, kApothem) > 0 || r < kHole) return kAbsent;
        const double chamfer = std::max(0.0, r - kFace) * std::tan(30.0 * std::numbers::pi / 180.0);
        const double sink = std::max(0.0, kHole + kSink - r);
        return -std::max(chamfer, sink);
    }

private:
    static constexpr double kApothem = 4.0, kHole = 2.5, kSink = 0.3, kFace = 3.9;
};

}  // namespace

std::unique_ptr<Relief> make_ball() { return std::make_unique<Ball>(); }
std::unique_ptr<Relief> make_lego() { return std::make_unique<Lego>(); }
std::unique_ptr<Relief> make_nut() { return std::make_unique<Nut>(); }

}  // namespace vkfuse::sim

// The solid objects: coin, lego brick, ball, screw, nut (sim/relief.hpp).
#include <cmath>
#include <numbers>
#include <vector>

#include "sim/relief.hpp"
#include "sim/shapes.hpp"

namespace vkfuse::sim {

// Both faces of a coin: a raised rim, a ring of beads and a bas-relief design - a profile portrait or the value within a wreath.
// Proportions of a 14 mm coin, relief about 0.1 mm as struck coins have.

namespace {

constexpr double kRadius = 7.0;
constexpr double kRimWidth = 0.6;
constexpr double kEdgeRound = 0.3;   // the rounded outer edge of the rim
constexpr double kFieldDepth = 0.12;  // the flat field sits below the rim top
constexpr double kRelief = 0.10;      // design height above the field
constexpr int kBeads = 72;
constexpr double kBeadRing = kRadius - 1.0, kBeadRadius = 0.16;

class Coin final : public Relief {
public:
    explicit Coin(bool heads) : heads_(heads) {
        if (heads_) return;
        value_ = lettering("10", 4.0, {0.0, -0.4});
        // Two olive branches along the rim, seven leaves each, lying along the branch.
        for (int side : {-1, 1})
            for (int i = 0; i < 7; ++i) {
                const double a = (100.0 + 18.0 * i) * std::numbers::pi / 180.0;
                leaves_.push_back({side * -4.2 * std::cos(a), 4.2 * std::sin(a), std::sin(a), side * std::cos(a)});
            }
    }

    double height(double u, double v) const override {
        const double r = std::hypot(u, v);
        if (r > kRadius) return kAbsent;
        if (r > kRadius - kEdgeRound) {  // quarter-round edge
            const double t = r - (kRadius - kEdgeRound);
            return -kEdgeRound + std::sqrt(kEdgeRound * kEdgeRound - t * t);
        }
        const double rim = smoothstep(kRadius - kRimWidth - 0.15, kRadius - kRimWidth, r);
        const double design = heads_ ? portrait(u, v) : reverse(u, v);
        return -kFieldDepth + std::max(rim * kFieldDepth, std::max(beads(u, v), design) * kRelief);
    }

private:
    static double beads(double u, double v) {
        const double step = 2 * std::numbers::pi / kBeads;
        const double a = std::round(std::atan2(v, u) / step) * step;
        const double d = std::hypot(u - kBeadRing * std::cos(a), v - kBeadRing * std::sin(a));
        return ridge(d, kBeadRadius);
    }

    // A head facing left: skull, face with nose and chin, neck, and the hair
    // as grooves, rising like a bas-relief toward its middle.
    static double portrait(double u, double v) {
        const double skull = ellipse_sdf(u - 0.4, v + 0.6, 2.4, 2.7);
        const double face = ellipse_sdf(u + 1.2, v - 0.4, 1.4, 2.0);
        const double nose = ellipse_sdf(u + 2.5, v - 0.1, 0.5, 0.35);
        const double neck = std::max(std::abs(u - 0.3) - 1.2, std::abs(v - 2.8) - 1.4);
        const double head = std::min({skull, face, nose, neck});
        double h = 0.55 + 0.45 * bevel(head, 0.8);  // rounded up toward the middle
        if (head >= 0) return 0;
        h *= bevel(head, 0.12);
        // Hair: wavy grooves over the back of the skull, an eye and an ear.
        const double hair = smoothstep(-0.2, 0.4, u - 0.3 * v) * 0.35 * (0.5 + 0.5 * std::sin(9.0 * v + 2.0 * std::sin(3.0 * u)));
        const double ear = ridge(std::abs(ellipse_sdf(u - 0.9, v - 0.1, 0.45, 0.6)), 0.12) * 0.3;
        const double eye = ridge(std::hypot(u + 1.6, v + 0.4), 0.25) * 0.3;
        return std::max(0.0, h - hair - ear - eye);
    }

    // The value within the wreath.
    double reverse(double u, double v) const {
        double relief = ridge(value_.distance({u, v}, 0.35), 0.35);
        for (const Leaf& leaf : leaves_) {
            // Into the leaf's own frame, its long axis along the branch.
            const double du = u - leaf.u, dv = v - leaf.v;
            const double along = du * leaf.cos + dv * leaf.sin, across = -du * leaf.sin + dv * leaf.cos;
            relief = std::max(relief, bevel(ellipse_sdf(along, across, 0.35, 0.8), 0.2));
        }
        return relief;
    }

    struct Leaf {
        double u, v, cos, sin;  // centre, and the direction of the branch there
    };
    bool heads_;
    Strokes value_;
    std::vector<Leaf> leaves_;
};

}  // namespace

std::unique_ptr<Relief> make_coin(bool heads) { return std::make_unique<Coin>(heads); }

// Solid objects with plain faces (sim/relief.hpp): a ball, the top of a
// 2x2 LEGO brick with its studs, and a hex nut. Standard dimensions in mm.

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

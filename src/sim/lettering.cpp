// Stroked lettering and the text relief (sim/relief.hpp).
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sim/relief.hpp"
#include "sim/shapes.hpp"

namespace vkfuse::sim {

// Embossed text: "DIGIT" in 5 mm capitals raised 0.3 mm with rounded strokes,
// on a plate 17 x 8 mm with rounded corners.

namespace {

class Text final : public Relief {
public:
    Text() : strokes_(lettering("DIGIT", 5.0, {0.0, 0.0})) {}

    double height(double u, double v) const override {
        // Rounded-rectangle plate: distance outside a 15 x 6 core, corner radius 1.
        const double du = std::max(std::abs(u) - 7.5, 0.0), dv = std::max(std::abs(v) - 3.0, 0.0);
        if (std::hypot(du, dv) > 1.0) return kAbsent;
        return kRaise * (ridge(strokes_.distance({u, v}, kStroke), kStroke) - 1.0);
    }

private:
    static constexpr double kRaise = 0.3, kStroke = 0.45;
    Strokes strokes_;
};

}  // namespace

std::unique_ptr<Relief> make_text() { return std::make_unique<Text>(); }

// Stroke font (sim/relief.hpp). Glyphs are drawn in a box of height 1
// (v down) and their own advance width; curves are polylines of arcs.

namespace {

struct Glyph {
    double advance = 0;
    std::vector<Polyline> strokes;
};

// Points on an elliptic arc from angle a0 to a1 (degrees, v down, 0 = +u).
Polyline arc(Point c, double ru, double rv, double a0, double a1, int pieces = 12) {
    Polyline line;
    for (int i = 0; i <= pieces; ++i) {
        const double a = (a0 + (a1 - a0) * i / pieces) * std::numbers::pi / 180.0;
        line.push_back({c.u + ru * std::cos(a), c.v + rv * std::sin(a)});
    }
    return line;
}

Glyph glyph(char ch) {
    switch (ch) {
        case '0': return {0.6, {arc({0.3, 0.5}, 0.3, 0.5, 0, 360, 24)}};
        case 'O': return {0.8, {arc({0.4, 0.5}, 0.4, 0.5, 0, 360, 24)}};
        case '1': return {0.5, {{{0.1, 0.2}, {0.3, 0.0}, {0.3, 1.0}}, {{0.1, 1.0}, {0.5, 1.0}}}};
        case 'D': {
            Polyline bowl = arc({0.3, 0.5}, 0.45, 0.5, -90, 90);
            bowl.insert(bowl.begin(), Point{0.0, 0.0});
            bowl.push_back({0.0, 1.0});
            bowl.push_back({0.0, 0.0});
            return {0.8, {bowl}};
        }
        case 'E': return {0.6, {{{0.6, 0.0}, {0.0, 0.0}, {0.0, 1.0}, {0.6, 1.0}}, {{0.0, 0.5}, {0.45, 0.5}}}};
        case 'G': {
            Polyline bowl = arc({0.4, 0.5}, 0.4, 0.5, -40, -320, 20);
            bowl.push_back({0.8, 0.55});
            bowl.push_back({0.45, 0.55});
            return {0.8, {bowl}};
        }
        case 'I': return {0.3, {{{0.15, 0.0}, {0.15, 1.0}}, {{0.0, 0.0}, {0.3, 0.0}}, {{0.0, 1.0}, {0.3, 1.0}}}};
        case 'L': return {0.6, {{{0.0, 0.0}, {0.0, 1.0}, {0.6, 1.0}}}};
        case 'T': return {0.7, {{{0.0, 0.0}, {0.7, 0.0}}, {{0.35, 0.0}, {0.35, 1.0}}}};
        default: throw std::logic_error(std::string("sim_glyphs: no glyph for '") + ch + "'");
    }
}

constexpr double kSpacing = 0.25;  // between glyphs, in units of the height

}  // namespace

std::vector<Polyline> text_strokes(std::string_view text, double height_mm, Point centre) {
    double width = 0;
    for (char ch : text) width += glyph(ch).advance + kSpacing;
    width -= kSpacing;
    std::vector<Polyline> out;
    double pen = -0.5 * width;
    for (char ch : text) {
        const Glyph g = glyph(ch);
        for (const Polyline& stroke : g.strokes) {
            Polyline placed;
            for (Point p : stroke)
                placed.push_back({centre.u + (pen + p.u) * height_mm, centre.v + (p.v - 0.5) * height_mm});
            out.push_back(std::move(placed));
        }
        pen += g.advance + kSpacing;
    }
    return out;
}

}  // namespace vkfuse::sim

// sim/shapes.hpp - small 2-D shape helpers the objects' height fields
// are built from: signed distances (negative inside) and smooth profiles.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

namespace vkfuse::sim {

inline double smoothstep(double edge0, double edge1, double x) {
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// A raised feature's profile across its border: 0 outside (sdf >= 0), rising
// to 1 over `bevel` mm inside, so relief has sloped, not vertical, walls.
inline double bevel(double sdf, double bevel_mm) { return smoothstep(0.0, bevel_mm, -sdf); }

// A rounded ridge of half-width w at distance d from its centre line: 1 on the
// line, 0 from w on, smooth (like an embossed stroke or a wire).
inline double ridge(double d, double w) {
    return d >= w ? 0.0 : 0.5 * (1.0 + std::cos(std::numbers::pi * d / w));
}

// Approximate signed distance to an axis-aligned ellipse (exact for circles,
// close near the border for moderate eccentricity, which is where it is used).
inline double ellipse_sdf(double u, double v, double ru, double rv) {
    return (std::hypot(u / ru, v / rv) - 1.0) * std::min(ru, rv);
}

// Signed distance to a regular hexagon with flats at +-apothem in v.
inline double hexagon_sdf(double u, double v, double apothem) {
    u = std::abs(u);
    v = std::abs(v);
    const double c = std::numbers::sqrt3 / 2.0;  // cos 30
    return std::max(v, c * u + 0.5 * v) - apothem;
}

struct Point {
    double u, v;
};

// Distance from p to the segment a-b.
inline double segment_distance(Point p, Point a, Point b) {
    const double bu = b.u - a.u, bv = b.v - a.v;
    const double len2 = bu * bu + bv * bv;
    const double t = len2 > 0 ? std::clamp(((p.u - a.u) * bu + (p.v - a.v) * bv) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(p.u - a.u - t * bu, p.v - a.v - t * bv);
}

// Strokes: polylines (of glyphs, say) and the distance to the nearest one.
using Polyline = std::vector<Point>;

class Strokes {
public:
    Strokes() = default;
    explicit Strokes(std::vector<Polyline> lines) : lines_(std::move(lines)) {
        for (const Polyline& line : lines_) {
            Box b{1e9, 1e9, -1e9, -1e9};
            for (Point p : line) b = {std::min(b.u0, p.u), std::min(b.v0, p.v), std::max(b.u1, p.u), std::max(b.v1, p.v)};
            boxes_.push_back(b);
        }
    }

    // Distance from p to the nearest stroke, or `beyond` if none is closer:
    // callers only care within a stroke's width, and the bounding boxes let
    // most polylines be skipped without looking at their segments.
    double distance(Point p, double beyond) const {
        double best = beyond;
        for (std::size_t i = 0; i < lines_.size(); ++i) {
            const Box& b = boxes_[i];
            if (p.u < b.u0 - best || p.u > b.u1 + best || p.v < b.v0 - best || p.v > b.v1 + best) continue;
            const Polyline& line = lines_[i];
            for (std::size_t k = 0; k + 1 < line.size(); ++k) best = std::min(best, segment_distance(p, line[k], line[k + 1]));
        }
        return best;
    }

private:
    struct Box {
        double u0, v0, u1, v1;
    };
    std::vector<Polyline> lines_;
    std::vector<Box> boxes_;
};

// Deterministic hash of a grid cell to [0, 1): fixed object textures that do
// not depend on the sensor's noise seed.
inline double cell_hash(int i, int j, int salt) {
    std::uint64_t h = std::uint64_t(std::int64_t(i)) * 0x9E3779B97F4A7C15ull ^
                      std::uint64_t(std::int64_t(j)) * 0xC2B2AE3D27D4EB4Full ^ std::uint64_t(salt) * 0x165667B19E3779F9ull;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 29;
    return double(h >> 11) * 0x1.0p-53;
}

}  // namespace vkfuse::sim

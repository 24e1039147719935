// sim/relief.hpp - the objects pressed into the gel, as height fields, and the
// stroked lettering some of them carry.
#pragma once
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sim/raster.hpp"
#include "sim/shapes.hpp"

namespace vkfuse::sim {

// The objects the simulated DIGIT can be pressed with: each a height field of
// the face that touches the gel.

// Height (mm) off the object: far below anything the gel can reach.
inline constexpr double kAbsent = -1e3;

// An object's touching face: height(u, v) in mm at (u, v) mm from the
// object's centre (u right, v down), <= 0, with 0 the first point that
// touches the gel, kAbsent where the object is not.
class Relief {
public:
    virtual ~Relief() = default;
    virtual double height(double u, double v) const = 0;
};

// Built-in objects, in the order SimDigit::objects() lists them.
std::vector<std::string> relief_names();
// nullptr for an unknown name; "nothing" gives a Relief that is absent everywhere.
std::unique_ptr<Relief> make_relief(std::string_view name);

// The relief sampled on the camera grid with its centre at (cx_mm, cy_mm),
// each pixel the mean of 2x2 samples so that steps do not alias.
Raster sample_relief(const Relief& relief, const Grid& grid, double cx_mm, double cy_mm);

// Factories of the individual objects (one file per family).
std::unique_ptr<Relief> make_coin(bool heads);
std::unique_ptr<Relief> make_lego();
std::unique_ptr<Relief> make_ball();
std::unique_ptr<Relief> make_screw();
std::unique_ptr<Relief> make_nut();
std::unique_ptr<Relief> make_velcro();
std::unique_ptr<Relief> make_file();
std::unique_ptr<Relief> make_text();

// A tiny stroke font for embossed lettering (the text object, the value on a
// coin, the logo on LEGO studs).

// Centre lines of text set in capitals of height_mm, centred on centre.
// Knows 0, 1, D, E, G, I, L, O, T (what the built-in objects use); any other
// character throws std::logic_error, a bug in an object's definition.
std::vector<Polyline> text_strokes(std::string_view text, double height_mm, Point centre);
inline Strokes lettering(std::string_view text, double height_mm, Point centre) {
    return Strokes(text_strokes(text, height_mm, centre));
}

}  // namespace vkfuse::sim

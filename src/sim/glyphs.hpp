// sim/glyphs.hpp - a tiny stroke font for embossed lettering (the
// text object, the value on a coin, the logo on LEGO studs).
#pragma once
#include <string_view>
#include <vector>

#include "sim/shapes.hpp"

namespace vkfuse::sim {

// Centre lines of text set in capitals of height_mm, centred on centre.
// Knows 0, 1, D, E, G, I, L, O, T (what the built-in objects use); any other
// character throws std::logic_error, a bug in an object's definition.
std::vector<Polyline> text_strokes(std::string_view text, double height_mm, Point centre);
inline Strokes lettering(std::string_view text, double height_mm, Point centre) {
    return Strokes(text_strokes(text, height_mm, centre));
}

}  // namespace vkfuse::sim

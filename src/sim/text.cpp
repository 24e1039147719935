// Embossed text (sim/relief.hpp): "DIGIT" in 5 mm capitals raised
// 0.3 mm with rounded strokes, on a plate 17 x 8 mm with rounded corners.
#include <cmath>

#include "sim/glyphs.hpp"
#include "sim/relief.hpp"
#include "sim/shapes.hpp"

namespace vkfuse::sim {
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

}  // namespace vkfuse::sim

// The catalogue of built-in objects and their sampling (sim/relief.hpp).
#include "sim/relief.hpp"

#include <functional>
#include <utility>

namespace vkfuse::sim {
namespace {

class Nothing final : public Relief {
public:
    double height(double, double) const override { return kAbsent; }
};

using Factory = std::function<std::unique_ptr<Relief>()>;

const std::vector<std::pair<std::string, Factory>>& catalogue() {
    static const std::vector<std::pair<std::string, Factory>> table{
        {"nothing", [] { return std::unique_ptr<Relief>(std::make_unique<Nothing>()); }},
        {"coin-heads", [] { return make_coin(true); }},
        {"coin-tails", [] { return make_coin(false); }},
        {"lego", make_lego},
        {"ball", make_ball},
        {"screw", make_screw},
        {"nut", make_nut},
        {"velcro", make_velcro},
        {"file", make_file},
        {"text", make_text},
    };
    return table;
}

}  // namespace

std::vector<std::string> relief_names() {
    std::vector<std::string> names;
    for (const auto& entry : catalogue()) names.push_back(entry.first);
    return names;
}

std::unique_ptr<Relief> make_relief(std::string_view name) {
    if (name == "coin") name = "coin-heads";
    for (const auto& [known, factory] : catalogue())
        if (known == name) return factory();
    return nullptr;
}

Raster sample_relief(const Relief& relief, const Grid& grid, double cx_mm, double cy_mm) {
    Raster out(grid);
    const double q = 0.25 * grid.mm_per_px;  // 2x2 samples at +-1/4 pixel
    for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x < grid.width; ++x) {
            const double u = grid.x_mm(x) - cx_mm, v = grid.y_mm(y) - cy_mm;
            const double sum = relief.height(u - q, v - q) + relief.height(u + q, v - q) +
                               relief.height(u - q, v + q) + relief.height(u + q, v + q);
            out.at(y, x) = float(sum / 4);
        }
    return out;
}

}  // namespace vkfuse::sim

// Object -> gel -> per-LED images (sim/scene.hpp).
#include "sim/scene.hpp"

#include <stdexcept>

#include "sim/gel.hpp"
#include "sim/relief.hpp"

namespace vkfuse::sim {

LedImages render_scene(const Contact& contact, const Grid& grid, const LedRig& rig) {
    const auto relief = make_relief(contact.object);
    if (!relief) throw std::logic_error("render_scene: unknown object " + contact.object);  // validated by the caller
    const double cx = (contact.x - 0.5) * Grid::kFieldWidthMm;
    const double cy = (contact.y - 0.5) * Grid::kFieldHeightMm;
    const GelSurface gel = press_gel(sample_relief(*relief, grid, cx, cy), contact.depth_mm, grid);
    return render_led_images(gel, grid, rig);
}

}  // namespace vkfuse::sim

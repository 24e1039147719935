// sim/scene.hpp - an object pressed into the gel, as the camera sees
// it under each LED: everything about a frame that does not change per frame.
#pragma once
#include <string>

#include "sim/optics.hpp"

namespace vkfuse::sim {

struct Contact {
    std::string object = "nothing";  // a name make_relief knows
    double depth_mm = 0;
    double x = 0.5, y = 0.5;         // centre, fractions of the field
};

// The per-LED camera images of the gel with contact pressed in.
LedImages render_scene(const Contact& contact, const Grid& grid, const LedRig& rig);

}  // namespace vkfuse::sim

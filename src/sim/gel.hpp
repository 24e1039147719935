// sim/gel.hpp - the elastomer: an object's relief pressed into the
// gel becomes a smooth displacement field of the membrane the camera films.
#pragma once
#include "sim/raster.hpp"

namespace vkfuse::sim {

// The membrane: displacement toward the camera (mm) and unit normals facing it.
struct GelSurface {
    Raster height;
    Raster nx, ny, nz;
    float max_height = 0;
};

// The undisturbed gel: flat, normals straight at the camera.
GelSurface flat_gel(const Grid& grid);

// relief: the object's surface height (mm, <= 0, 0 = first point to touch,
// kAbsent off the object) sampled on grid; depth_mm: how far it is pushed in
// past first touch. In contact the membrane follows the object; around it the
// elastomer falls off smoothly (a blurred copy of the indentation, the shape
// a soft layer takes under a load), and the membrane's own stiffness rounds
// edges finer than about 0.05 mm.
GelSurface press_gel(const Raster& relief, double depth_mm, const Grid& grid);

}  // namespace vkfuse::sim

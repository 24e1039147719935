// sim/calibration.hpp - how the simulator's LED light fields are
// obtained from a real DIGIT frame, so the stored constants can be re-derived
// (and are, by tests/test_cpu_sim_calibration.cpp).
#pragma once
#include <array>

#include "sim/lighting.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::sim {

// frame: a real DIGIT frame at (15,15,15) with nothing pressed, landscape
// 320x240 RGB in [0, 1]. Averages it over 8x8 blocks (the low-frequency
// structure; noise and compression artefacts average out) and solves, by
// linear least squares over all blocks and channels, for the three cubic
// fields whose mix through crosstalk reproduces it:
//   frame_c(x, y) ~ sum_k crosstalk[c][k] * field_k(x, y)   (DN)
// Throws std::invalid_argument for any other frame shape.
std::array<LightField, 3> fit_light_fields(const ImageD& frame, const Crosstalk& crosstalk);

// digit_interface's portrait frame (W x H = 240 x 320) back to the sensor's
// landscape readout: landscape(r, c) = portrait(H - 1 - c, r).
ImageD landscape_from_portrait(const ImageD& portrait);

}  // namespace vkfuse::sim

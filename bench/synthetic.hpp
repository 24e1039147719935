// Deterministic tactile-sensor frames: what a DIGIT sees of a gel pressed by an
// object, lit by one LED per frame. Real enough for fusion to have work to do
// (smooth illumination gradients, a contact with fine texture, sensor noise),
// reproducible bit for bit from (scene, LED) so every backend and the peers
// fuse the same inputs.
#pragma once
#include <cstdint>

#include "axes.hpp"
#include "vkfuse/image.hpp"

namespace vkfuse::bench {

// One sensor's contact, derived from its scene number.
struct TactileScene {
    double cx = 0, cy = 0;   // contact centre, in image heights from the image centre
    double radius = 0.2;     // contact radius, in image heights
    double depth = 0.05;     // indentation depth at the centre
    double ridges = 40;      // spatial frequency of the object's texture (radians per image height)
    double ridge_angle = 0;  // direction of that texture
    double gain = 1;         // this unit's LED brightness (units differ by a few percent)
    std::uint64_t seed = 0;  // noise seed
};

TactileScene make_scene(int scene);

// RGB frame of the scene lit by LED `led` of `leds` (LEDs evenly spaced around
// the gel, each its own colour), float32 in [0, 1].
Image tactile_frame(Size size, const TactileScene& scene, int led, int leds);

// The scene's gel without contact under all LEDs at once, without noise: the
// sensor's reference image for the background difference metric.
Image tactile_background(Size size, const TactileScene& scene, int leds);

}  // namespace vkfuse::bench

// The frames of one workload: S sensors x K frames plus each sensor's
#pragma once
#include <cstdint>
#include <vector>

#include "axes.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::bench {

// The frames of one workload: S sensors x K frames plus each sensor's
// background, generated once and fed unchanged to every backend and peer.

// Distinct scenes generated per workload. Sensors beyond this many reuse the
// scenes' frames (sensor s shows scene s % kMaxScenes): a plan still uploads
// and fuses S*K frames, while host memory and generation time stay bounded.
inline constexpr int kMaxScenes = 8;

class Inputs {
public:
    Inputs(Size size, int frames, int sensors);

    Size size() const { return size_; }
    int frames() const { return frames_; }
    int sensors() const { return sensors_; }
    int scene_of(int sensor) const { return sensor % scenes_; }
    const Image& frame(int sensor, int k) const { return images_[std::size_t(scene_of(sensor) * frames_ + k)]; }
    const Image& background(int sensor) const { return backgrounds_[std::size_t(scene_of(sensor))]; }
    // Every frame, sensor-major (sensor s, frame k at s * K + k), as Plan::run takes them.
    std::vector<FrameView> views() const;
    std::size_t frame_bytes() const { return std::size_t(size_.width) * size_.height * 3 * sizeof(float); }

private:
    Size size_;
    int frames_, sensors_, scenes_;
    std::vector<Image> images_;       // scene-major: scene i, frame k at i * K + k
    std::vector<Image> backgrounds_;  // one per scene
};

// Deterministic tactile-sensor frames: what a DIGIT sees of a gel pressed by an
// object, lit by one LED per frame. Real enough for fusion to have work to do
// (smooth illumination gradients, a contact with fine texture, sensor noise),
// reproducible bit for bit from (scene, LED) so every backend and the peers
// fuse the same inputs.

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

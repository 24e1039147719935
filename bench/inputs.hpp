// The frames of one workload: S sensors x K frames plus each sensor's
// background, generated once and fed unchanged to every backend and peer.
#pragma once
#include <vector>

#include "axes.hpp"
#include "vkfuse/image.hpp"

namespace vkfuse::bench {

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

}  // namespace vkfuse::bench

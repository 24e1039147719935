#include "inputs.hpp"

#include <algorithm>

#include "synthetic.hpp"

namespace vkfuse::bench {

Inputs::Inputs(Size size, int frames, int sensors)
    : size_(size), frames_(frames), sensors_(sensors), scenes_(std::min(sensors, kMaxScenes)) {
    for (int i = 0; i < scenes_; ++i) {
        const TactileScene scene = make_scene(i);
        for (int k = 0; k < frames; ++k) images_.push_back(tactile_frame(size, scene, k, frames));
        backgrounds_.push_back(tactile_background(size, scene, frames));
    }
}

std::vector<FrameView> Inputs::views() const {
    std::vector<FrameView> out;
    for (int s = 0; s < sensors_; ++s)
        for (int k = 0; k < frames_; ++k) out.push_back(FrameView::of(frame(s, k)));
    return out;
}

}  // namespace vkfuse::bench

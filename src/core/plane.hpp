// core/plane.hpp - one channel of an image as a dense row-major grid of
// doubles: the unit the multi-scale transforms (pyramids, wavelets) work on.
#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include "vkfuse/core/image.hpp"

namespace vkfuse::core {

struct Plane {
    int height = 0;
    int width = 0;
    std::vector<double> data;  // row-major, data[y * width + x]

    Plane() = default;
    Plane(int h, int w) : height(h), width(w), data(std::size_t(h) * std::size_t(w)) {}

    double& at(int y, int x) { return data[std::size_t(y) * width + x]; }
    double at(int y, int x) const { return data[std::size_t(y) * width + x]; }
    bool same_shape(const Plane& o) const { return height == o.height && width == o.width; }
};

// Channel c of an interleaved HWC image, and the way back.
Plane extract_channel(const ImageD& image, int c);
void insert_channel(const Plane& plane, ImageD& image, int c);

// The top-left height x width corner of p (height <= p.height, width <= p.width).
// pywt's waverec2 returns an even size for odd inputs; this trims it back.
Plane crop(const Plane& p, int height, int width);

// Runs a single-plane fusion (K planes -> one) on every channel of K frames.
template <class PlaneFusion>
ImageD per_channel(std::span<const ImageD> frames, PlaneFusion fuse) {
    ImageD out(frames[0].height, frames[0].width, frames[0].channels);
    std::vector<Plane> planes(frames.size());
    for (int c = 0; c < out.channels; ++c) {
        for (std::size_t k = 0; k < frames.size(); ++k) planes[k] = extract_channel(frames[k], c);
        insert_channel(fuse(std::span<const Plane>(planes)), out, c);
    }
    return out;
}

}  // namespace vkfuse::core

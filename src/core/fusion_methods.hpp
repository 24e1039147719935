// core/fusion_methods.hpp - the fusion methods of docs/spec.md, one function each,
// on inputs fuse_reference() has already validated (one shape, right K and C).
#pragma once
#include <span>

#include "core/plane.hpp"
#include "vkfuse/fusion.hpp"
#include "vkfuse/image.hpp"

namespace vkfuse::core {

// Per pixel, whole images (K = 3, C = 3 for channel-sum).
ImageD fuse_channel_sum(std::span<const ImageD> frames);
ImageD fuse_brovey(std::span<const ImageD> frames);
// Per pixel and channel, the mean of the K frames (compensated sum).
ImageD fuse_mean(std::span<const ImageD> frames);

// Multi-scale, one channel of every frame at a time.
Plane fuse_laplacian(std::span<const Plane> frames, int levels, Rule base, Rule detail);
Plane fuse_wavelet(std::span<const Plane> frames, const FusionSpec& spec);

}  // namespace vkfuse::core

// core/fusion_methods.hpp - the fusion methods of docs/spec.md, one function each,
// on inputs fuse_reference() has already validated (one shape, right K and C).
#pragma once
#include <span>

#include "core/plane.hpp"
#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::core {

// Each method's reference on whole frames, the signature of its row in the
// method table (core/method_table.hpp).
ImageD fuse_channel_sum(std::span<const ImageD> frames, const FusionSpec& spec);  // K = 3, C = 3
ImageD fuse_brovey(std::span<const ImageD> frames, const FusionSpec& spec);
ImageD fuse_laplacian(std::span<const ImageD> frames, const FusionSpec& spec);
ImageD fuse_wavelet(std::span<const ImageD> frames, const FusionSpec& spec);

// Per pixel and channel, the mean of the K frames (compensated sum): the
// background model's, not a fusion method.
ImageD fuse_mean(std::span<const ImageD> frames);

// The multi-scale methods one channel of every frame at a time.
Plane fuse_laplacian(std::span<const Plane> frames, int levels, Rule base, Rule detail);
Plane fuse_wavelet(std::span<const Plane> frames, const FusionSpec& spec);

}  // namespace vkfuse::core

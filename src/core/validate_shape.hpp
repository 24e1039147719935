// core/validate_shape.hpp - the checks every plan and fusion makes of its frames' shape.
#pragma once
#include <span>

#include "vkfuse/core/image.hpp"

namespace vkfuse::core {

// Throws Error(InvalidArgument) with a one-line reason unless height, width
// >= 1, channels is 1 or 3 and frames >= 1.
void validate_shape(int height, int width, int channels, int frames);

// Throws Error(Shape) unless every frame has frame 1's shape, and
// Error(Numeric) at a NaN or infinity; messages number frames from 1, as
// docs/spec.md writes I_1 .. I_K.
void check_frames(std::span<const ImageD> frames);

}  // namespace vkfuse::core

// Shared helpers for the test executables.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::test {

// Deterministic pseudo-random image, values float32-representable in [0, 1].
ImageD random_image(int height, int width, int channels, std::uint32_t seed);
// A smooth image with edges and texture (closer to a tactile frame than noise).
ImageD structured_image(int height, int width, int channels, std::uint32_t seed);
// Largest |a - b| over all samples; a and b must have one shape.
double max_abs_diff(const ImageD& a, const ImageD& b);
double max_abs_diff(const Image& a, const ImageD& b);
// The Laplacian and every wavelet in both modes (default levels), max-abs for
// base and detail: every transform whose coefficients a max-abs rule picks.
std::vector<FusionSpec> every_pyramid_and_wavelet_max_abs();
// Path of a file under tests/data.
std::string data_path(const std::string& name);

}  // namespace vkfuse::test

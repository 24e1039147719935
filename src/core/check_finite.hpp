// core/check_finite.hpp - the reference path refuses NaN and Inf (docs/spec.md: they
// are bad input), so rules like max-abs never have to order them.
#pragma once
#include <string>

#include "vkfuse/core/image.hpp"

namespace vkfuse::core {

// Throws Error(Numeric) "<what>: NaN at row y, column x, channel c" (or Inf).
void require_finite(const ImageD& image, const std::string& what);

// Throws Error(Numeric) "<what> value v at row y, column x, channel c lies
// beyond float32's range" for the first |v| > FLT_MAX: a double result that
// cannot be stored as float32 without becoming Inf.
void require_float32_range(const ImageD& image, const std::string& what);

}  // namespace vkfuse::core

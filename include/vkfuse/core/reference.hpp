// vkfuse/core/reference.hpp - the CPU reference path: double precision, exactly
// docs/spec.md. It is the oracle every GPU result is tested against, and the
// backend `vkfuse --backend cpu` uses.
#pragma once
#include <span>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/core/metrics.hpp"

namespace vkfuse {

// Fuses K frames of one shape. Validates first (see validate()); throws Error.
ImageD fuse_reference(std::span<const ImageD> frames, const FusionSpec& spec);

// The metrics of img that `which` names: background difference only when a
// background is given (it must have img's shape, else Error(Shape)); the
// others read NaN (Metrics).
Metrics metrics_reference(const ImageD& img, const ImageD* background = nullptr,
                          MetricSet which = MetricSet::all());

}  // namespace vkfuse

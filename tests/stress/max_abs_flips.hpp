// max_abs_flips.hpp - tells a max-abs near-tie from a wrong result.
//
// Where two frames' wavelet coefficients are equal in magnitude up to
// float's rounding (typically opposite in sign), float may pick the other
// frame than double does (README "Accuracy"). One such flip at a deep level
// moves a whole patch of the fused image by up to twice the coefficient, so
// counting samples beyond 1e-5 cannot separate it from a bug. This does:
// it finds every near-tie of the double reference, synthesises the effect of
// taking the runner-up there (waverec2 is linear), and keeps each flip that
// brings the reference closer to the GPU's image. A correct GPU result then
// matches the adjusted reference at every sample; a wrong rule, border or
// sensor leaves samples out that no near-tie explains.
#pragma once
#include <span>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::test {

struct MaxAbsFlips {
    ImageD adjusted;     // the reference with the kept flips applied
    int near_ties = 0;   // decisions double took by a margin float cannot resolve
    int flipped = 0;     // of those, the ones the GPU's image shows taken the other way
};

// spec: a wavelet spec; frames: the K frames of one sensor (double copies of
// the GPU's float inputs); gpu: that sensor's fused image.
MaxAbsFlips explain_max_abs_flips(std::span<const ImageD> frames, const FusionSpec& spec, const Image& gpu);

}  // namespace vkfuse::test

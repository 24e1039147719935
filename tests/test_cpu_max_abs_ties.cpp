// Exact max-abs ties in the CPU reference (docs/spec.md "Rules": ties go to the
// lowest frame index), through every pyramid and wavelet: the coefficients of
// -A are exactly the negated coefficients of A, so fusing A with -A under
// max-abs must give A back, and -A with A must give -A.
// test_vk_max_abs_ties.cpp asks the same of the GPU.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_support.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

ImageD scaled(const ImageD& a, double k) {
    ImageD out = a;
    for (double& v : out.data) v *= k;
    return out;
}

TEST(CpuMaxAbsTies, TiesGoToTheLowestFrameThroughEveryTransform) {
    ImageD a = structured_image(75, 90, 1, 5);  // carries the default 3 levels of bior4.4
    for (double& v : a.data) v -= 0.4;  // both signs
    const ImageD neg = scaled(a, -1.0), half = scaled(a, 0.5);
    for (const FusionSpec& spec : every_pyramid_and_wavelet_max_abs()) {
        SCOPED_TRACE(std::string(to_string(spec.method)) + " " + std::string(to_string(spec.wavelet)) + "/" +
                     std::string(to_string(spec.mode)));
        const std::vector<ImageD> a_first{a, neg}, neg_first{neg, a}, three{a, half, neg}, three_neg{neg, half, a};
        EXPECT_LE(max_abs_diff(fuse_reference(a_first, spec), a), 1e-9);
        EXPECT_LE(max_abs_diff(fuse_reference(neg_first, spec), neg), 1e-9);
        EXPECT_LE(max_abs_diff(fuse_reference(three, spec), a), 1e-9);
        EXPECT_LE(max_abs_diff(fuse_reference(three_neg, spec), neg), 1e-9);
    }
}

}  // namespace
}  // namespace vkfuse::test

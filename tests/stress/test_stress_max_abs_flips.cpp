// The near-tie oracle of the stress tests (max_abs_flips.hpp) must explain a
// flipped decision and nothing else, or the tests that lean on it could not fail.
#include <gtest/gtest.h>

#include <vector>

#include "max_abs_flips.hpp"
#include "stress_support.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

// a and -a: every detail coefficient is an exact max-abs tie (negation is
// exact), which double settles for frame 1; fusing (-a, a) settles every one
// the other way, as a float result might at a few of them.
struct TiedPair {
    std::vector<ImageD> frames;
    Image other_way;
};

TiedPair tied_pair(const FusionSpec& spec) {
    const ImageD a = convert<double>(structured_frame(8, 8, 1, 3));
    ImageD minus_a = a;
    for (double& v : minus_a.data) v = -v;
    const std::vector<ImageD> swapped{minus_a, a};
    return {{a, minus_a}, convert<float>(fuse_reference(swapped, spec))};
}

TEST(StressMaxAbsFlips, ExplainsDecisionsTakenTheOtherWay) {
    const FusionSpec spec = wavelet_spec(Wavelet::Haar, WaveletMode::Periodization, 1);
    const TiedPair p = tied_pair(spec);
    ASSERT_GT(compare(p.other_way, fuse_reference(p.frames, spec), 1e-5).over, 0u) << "the flips must show";
    const MaxAbsFlips flips = explain_max_abs_flips(p.frames, spec, p.other_way);
    EXPECT_EQ(flips.near_ties, 48);  // the three 4 x 4 detail bands
    EXPECT_GT(flips.flipped, 0);
    EXPECT_EQ(compare(p.other_way, flips.adjusted, 1e-5).over, 0u);
}

TEST(StressMaxAbsFlips, DoesNotExplainAWrongSample) {
    const FusionSpec spec = wavelet_spec(Wavelet::Db2, WaveletMode::Symmetric, 1);
    const TiedPair p = tied_pair(spec);
    ASSERT_EQ(compare(p.other_way, explain_max_abs_flips(p.frames, spec, p.other_way).adjusted, 1e-5).over, 0u)
        << "db2's flips alone are explained";
    Image wrong = p.other_way;
    wrong.data[27] += 1e-3f;
    const MaxAbsFlips flips = explain_max_abs_flips(p.frames, spec, wrong);
    EXPECT_GE(compare(wrong, flips.adjusted, 1e-5).over, 1u);
}

TEST(StressMaxAbsFlips, FindsNoTieWhereNoneIs) {
    const FusionSpec spec = wavelet_spec(Wavelet::Bior44, WaveletMode::Periodization, 1);
    const std::vector<ImageD> frames{convert<double>(random_frame(24, 24, 1, 5)),
                                     convert<double>(random_frame(24, 24, 1, 6))};
    const ImageD ref = fuse_reference(frames, spec);
    const MaxAbsFlips flips = explain_max_abs_flips(frames, spec, convert<float>(ref));
    EXPECT_EQ(flips.flipped, 0);
    EXPECT_EQ(compare(convert<float>(ref), flips.adjusted, 1e-6).over, 0u);
}

}  // namespace
}  // namespace vkfuse::test

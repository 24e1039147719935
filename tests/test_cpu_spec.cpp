// FusionSpec names, parsing and validate() messages (include/vkfuse/core/fusion.hpp).
#include <gtest/gtest.h>

#include <string>

#include "vkfuse/core/error.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse {
namespace {

// The message of the InvalidArgument error f throws ("" if none).
template <class F>
std::string invalid_argument_message(F f) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::InvalidArgument) << e.what();
        return e.what();
    }
    return "";
}

FusionSpec wavelet_spec(Wavelet w, int levels) {
    FusionSpec s;
    s.method = Method::Wavelet;
    s.wavelet = w;
    s.levels = levels;
    return s;
}

TEST(CpuSpec, NamesRoundTrip) {
    for (Method m : {Method::ChannelSum, Method::Brovey, Method::Laplacian, Method::Wavelet})
        EXPECT_EQ(parse_method(to_string(m)), m);
    for (Wavelet w : {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44})
        EXPECT_EQ(parse_wavelet(to_string(w)), w);
    for (WaveletMode m : {WaveletMode::Periodization, WaveletMode::Symmetric})
        EXPECT_EQ(parse_wavelet_mode(to_string(m)), m);
    for (Rule r : {Rule::MaxAbs, Rule::Mean, Rule::Max, Rule::Min}) EXPECT_EQ(parse_rule(to_string(r)), r);
    EXPECT_EQ(to_string(Method::ChannelSum), "channel-sum");
    EXPECT_EQ(to_string(Wavelet::Bior22), "bior2.2");
    EXPECT_EQ(to_string(Rule::MaxAbs), "max-abs");
}

TEST(CpuSpec, UnknownNamesListTheValidOnes) {
    EXPECT_EQ(invalid_argument_message([] { parse_wavelet("db9"); }),
              "--wavelet: unknown wavelet \"db9\" (expected haar, db2, bior2.2, bior4.4)");
    EXPECT_EQ(invalid_argument_message([] { parse_method("passthrough"); }),
              "--method: unknown method \"passthrough\" (expected channel-sum, brovey, laplacian, wavelet)");
    EXPECT_EQ(invalid_argument_message([] { parse_wavelet_mode("zero"); }),
              "--mode: unknown mode \"zero\" (expected periodization, symmetric)");
    EXPECT_EQ(invalid_argument_message([] { parse_rule("median", "--detail-rule"); }),
              "--detail-rule: unknown rule \"median\" (expected max-abs, mean, max, min)");
    EXPECT_NE(invalid_argument_message([] { parse_rule("Mean"); }), "");  // names are case-sensitive
}

TEST(CpuSpec, FilterLengthsArePywtDecLen) {
    EXPECT_EQ(filter_length(Wavelet::Haar), 2);
    EXPECT_EQ(filter_length(Wavelet::Db2), 4);
    EXPECT_EQ(filter_length(Wavelet::Bior22), 6);
    EXPECT_EQ(filter_length(Wavelet::Bior44), 10);
}

TEST(CpuSpec, TooManyWaveletLevelsNamesTheLargestThatFits) {
    EXPECT_EQ(max_wavelet_levels(Wavelet::Bior44, 61, 97), 2);
    EXPECT_EQ(invalid_argument_message([] { validate(wavelet_spec(Wavelet::Bior44, 3), 61, 97, 3, 2); }),
              "--levels 3: a 61x97 image carries at most 2 levels of bior4.4");
    EXPECT_EQ(invalid_argument_message([] { validate(wavelet_spec(Wavelet::Bior44, 0), 20, 30, 1, 2); }),
              "--levels (default 3): a 20x30 image carries at most 1 level of bior4.4");
    EXPECT_EQ(invalid_argument_message([] { validate(wavelet_spec(Wavelet::Bior44, 1), 17, 300, 1, 2); }),
              "--levels 1: a 17x300 image is too small for bior4.4 (one level needs both sides >= 18)");
    EXPECT_EQ(invalid_argument_message([] { validate(wavelet_spec(Wavelet::Bior44, 2), 61, 97, 3, 2); }), "");
    EXPECT_EQ(invalid_argument_message([] { validate(wavelet_spec(Wavelet::Bior44, 1), 18, 18, 3, 2); }), "");
    EXPECT_EQ(invalid_argument_message([] { validate(wavelet_spec(Wavelet::Haar, 1), 2, 2, 1, 1); }), "");
}

TEST(CpuSpec, NegativeLevelsAreRejected) {
    FusionSpec s;
    s.method = Method::Laplacian;
    s.levels = -1;
    EXPECT_EQ(invalid_argument_message([&] { validate(s, 10, 10, 1, 2); }),
              "--levels -1: must be >= 0 (0 = method default)");
}

TEST(CpuSpec, FrameAndChannelCounts) {
    FusionSpec cs;
    cs.method = Method::ChannelSum;
    EXPECT_EQ(invalid_argument_message([&] { validate(cs, 4, 4, 3, 2); }),
              "--method channel-sum: needs exactly 3 frames (red, green, blue LED), got 2");
    EXPECT_EQ(invalid_argument_message([&] { validate(cs, 4, 4, 1, 3); }),
              "--method channel-sum: needs 3-channel (RGB) frames, got 1 channel(s)");
    EXPECT_EQ(invalid_argument_message([&] { validate(cs, 4, 4, 3, 3); }), "");
    FusionSpec lap;
    lap.method = Method::Laplacian;
    lap.levels = 9;  // any size carries any level count: pyrDown of 1 pixel is 1 pixel
    EXPECT_EQ(invalid_argument_message([&] { validate(lap, 1, 1, 1, 2); }), "");
    EXPECT_NE(invalid_argument_message([&] { validate(lap, 4, 4, 2, 2); }), "");
    EXPECT_NE(invalid_argument_message([&] { validate(lap, 0, 4, 1, 2); }), "");
    EXPECT_NE(invalid_argument_message([&] { validate(lap, 4, 4, 1, 0); }), "");
}

// Past 1 x 1 a Laplacian level repeats the one above; an absurd count used to
// allocate a level per unit (2^31 - 1 ran out of memory) instead of failing.
TEST(CpuSpec, LaplacianLevelsAreBoundedPastOnePixel) {
    FusionSpec lap;
    lap.method = Method::Laplacian;
    lap.levels = 32;
    EXPECT_EQ(invalid_argument_message([&] { validate(lap, 1, 1, 1, 2); }), "");
    lap.levels = 2147483647;
    EXPECT_EQ(invalid_argument_message([&] { validate(lap, 1, 1, 1, 2); }),
              "--levels 2147483647: a Laplacian pyramid takes at most 32 levels (31 reach 1x1 from any size)");
}

}  // namespace
}  // namespace vkfuse

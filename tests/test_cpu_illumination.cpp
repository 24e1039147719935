// LED layouts and illumination settings: text form, validation, sequences.
#include <gtest/gtest.h>

#include "expect_error.hpp"
#include "vkfuse/sensor/illumination.hpp"

namespace vkfuse {
namespace {

TEST(Illumination, DigitLayoutIsThreeChannelsUpToFifteen) {
    const LedLayout d = LedLayout::digit();
    EXPECT_EQ(d.model, "DIGIT");
    EXPECT_EQ(d.channels, 3);
    EXPECT_EQ(d.max_level, 15);
    EXPECT_EQ(d.names, (std::vector<std::string>{"r", "g", "b"}));
}

TEST(Illumination, Digit360LayoutIsEightRgbLeds) {
    const LedLayout d = LedLayout::digit360();
    EXPECT_EQ(d.channels, 24);
    EXPECT_EQ(d.max_level, 255);
    ASSERT_EQ(d.names.size(), 24u);
    EXPECT_EQ(d.names.front(), "led0.r");
    EXPECT_EQ(d.names[4], "led1.g");
    EXPECT_EQ(d.names.back(), "led7.b");
}

TEST(Illumination, ParsesAndPrintsBackTheSameText) {
    const Illumination i = Illumination::parse("15,0,7");
    EXPECT_EQ(i.levels(), (std::vector<int>{15, 0, 7}));
    EXPECT_EQ(i.level(2), 7);
    EXPECT_EQ(i.to_string(), "15,0,7");
    EXPECT_EQ(Illumination::parse(i.to_string()), i);
}

TEST(Illumination, MalformedTextIsAnErrorNamingIt) {
    using test::expect_error;
    const auto k = ErrorKind::InvalidArgument;
    expect_error([] { Illumination::parse(""); }, "illumination \"\"", k, "no levels");
    expect_error([] { Illumination::parse("15,,15"); }, "illumination \"15,,15\"", k, "level 2 is empty");
    expect_error([] { Illumination::parse("15,x,15"); }, "illumination \"15,x,15\"", k, "not a non-negative integer");
    expect_error([] { Illumination::parse("15, 15,15"); }, "illumination \"15, 15,15\"", k, "level 2");
    expect_error([] { Illumination::parse("-1,0,0"); }, "illumination \"-1,0,0\"", k, "level 1");
    expect_error([] { Illumination::parse("1.5,0,0"); }, "illumination \"1.5,0,0\"", k, "level 1");
    expect_error([] { Illumination::parse("99999999999,0,0"); }, "illumination \"99999999999,0,0\"", k, "out of range");
    expect_error([] { Illumination::parse("15,15,"); }, "illumination \"15,15,\"", k, "level 3 is empty");
}

TEST(Illumination, CheckRejectsWhatTheLayoutCannotShow) {
    using test::expect_error;
    const auto k = ErrorKind::InvalidArgument;
    const LedLayout digit = LedLayout::digit();
    EXPECT_NO_THROW(Illumination({0, 15, 0}).check(digit));
    expect_error([&] { Illumination({16, 0, 0}).check(digit); }, "illumination 16,0,0", k, "level 16 of r exceeds 15");
    expect_error([&] { Illumination({0, 0, -2}).check(digit); }, "illumination 0,0,-2", k, "level -2 of b is below 0");
    expect_error([&] { Illumination({15, 15}).check(digit); }, "illumination 15,15", k, "2 levels, DIGIT has 3");
    EXPECT_NO_THROW(Illumination(std::vector<int>(24, 255)).check(LedLayout::digit360()));
}

TEST(Illumination, SequencesSplitOnPlus) {
    const IlluminationSequence s = parse_sequence("15,15,15+0,15,0");
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0], Illumination({15, 15, 15}));
    EXPECT_EQ(s[1], Illumination({0, 15, 0}));
    EXPECT_EQ(to_string(s), "15,15,15+0,15,0");
    EXPECT_EQ(parse_sequence("1,2,3").size(), 1u);
}

TEST(Illumination, BadSequencesNameTheWholeTextAndTheSetting) {
    using test::expect_error;
    const auto k = ErrorKind::InvalidArgument;
    expect_error([] { parse_sequence(""); }, "illumination sequence \"\"", k, "no settings");
    expect_error([] { parse_sequence("15,15,15+"); }, "illumination sequence \"15,15,15+\"", k, "setting 2");
    expect_error([] { parse_sequence("15,15,15+0,a,0"); }, "illumination sequence \"15,15,15+0,a,0\"", k,
                 "setting 2: illumination \"0,a,0\"");
}

}  // namespace
}  // namespace vkfuse

namespace vkfuse {
namespace {

TEST(Illumination, FullMeansEveryChannelAtTheLayoutsTop) {
    const LedLayout digit = LedLayout::digit(), digit360 = LedLayout::digit360();
    EXPECT_TRUE(Illumination({15, 15, 15}).is_full(digit));
    EXPECT_FALSE(Illumination({15, 15, 14}).is_full(digit));
    EXPECT_FALSE(Illumination({0, 15, 0}).is_full(digit));
    EXPECT_FALSE(Illumination({15, 15}).is_full(digit));           // too few channels
    EXPECT_FALSE(Illumination({15, 15, 15, 15}).is_full(digit));   // too many
    EXPECT_FALSE(Illumination({15, 15, 15}).is_full(digit360));    // 24 channels, 0..255
    EXPECT_TRUE(Illumination(std::vector<int>(24, 255)).is_full(digit360));
}

}  // namespace
}  // namespace vkfuse

// cv::pyrDown / cv::pyrUp reimplemented in the CPU reference, against cv2 4.6
// on float64 (tests/data/peers/pyramid.bin).
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <stdexcept>
#include <string>

#include "core/pyramid.hpp"
#include "peer_file.hpp"

namespace vkfuse {
namespace {

using core::Plane;

const test::PeerFile& peers() {
    static const test::PeerFile file("pyramid.bin");
    return file;
}

TEST(CpuPyramid, PyrDownMatchesOpenCV) {
    const std::regex key(R"((\d+x\d+)/down)");
    double worst = 0;
    int cases = 0;
    for (const auto& [name, array] : peers().all()) {
        std::smatch m;
        if (!std::regex_match(name, m, key)) continue;
        const Plane down = core::pyr_down(peers().plane(m[1].str() + "/input"));
        const double err = test::max_abs_diff(down, peers().plane(name));
        EXPECT_LE(err, 1e-6) << name;
        worst = std::max(worst, err);
        ++cases;
    }
    EXPECT_EQ(cases, 7);
    std::printf("[peer] pyrDown: %d sizes, worst |err| = %.3g\n", cases, worst);
}

TEST(CpuPyramid, PyrUpMatchesOpenCVForEvenAndOddSizes) {
    const std::regex direct(R"((\d+x\d+)/up_(\d+)x(\d+))"), chained(R"((\d+x\d+)/down_up_(\d+)x(\d+))");
    double worst = 0;
    int cases = 0;
    for (const auto& [name, array] : peers().all()) {
        std::smatch m;
        Plane src;
        if (std::regex_match(name, m, direct)) src = peers().plane(m[1].str() + "/input");
        else if (std::regex_match(name, m, chained)) src = peers().plane(m[1].str() + "/down");
        else continue;
        const Plane up = core::pyr_up(src, std::stoi(m[2]), std::stoi(m[3]));
        const double err = test::max_abs_diff(up, peers().plane(name));
        EXPECT_LE(err, 1e-6) << name;
        worst = std::max(worst, err);
        ++cases;
    }
    EXPECT_EQ(cases, 5 * 4 + 2 * 2);
    std::printf("[peer] pyrUp: %d cases, worst |err| = %.3g\n", cases, worst);
}

TEST(CpuPyramid, PyrUpOddSizeEndsWithTheEvenFormula) {
    // OpenCV 4.6 keeps t0 = (s[n-2] + 7 s[n-1]) / 8 in the last column of a
    // 2n - 1 wide result (no replicate special case), same for rows.
    Plane s(1, 3);
    s.data = {1.0, 2.0, 10.0};
    const Plane odd = core::pyr_up(s, 1, 5), even = core::pyr_up(s, 1, 6);
    EXPECT_DOUBLE_EQ(odd.at(0, 4), (2.0 + 7 * 10.0) / 8);
    EXPECT_DOUBLE_EQ(even.at(0, 4), (2.0 + 7 * 10.0) / 8);
    EXPECT_DOUBLE_EQ(even.at(0, 5), 10.0);                 // right edge replicates
    EXPECT_DOUBLE_EQ(even.at(0, 0), (6 * 1.0 + 2 * 2.0) / 8);  // left edge reflects
}

TEST(CpuPyramid, PyrUpRejectsSizesOtherThanTwiceOrTwiceMinusOne) {
    const Plane s(3, 4);
    EXPECT_THROW(core::pyr_up(s, 7, 8), std::invalid_argument);
    EXPECT_THROW(core::pyr_up(s, 6, 9), std::invalid_argument);
    EXPECT_THROW(core::pyr_up(s, 4, 8), std::invalid_argument);
    EXPECT_NO_THROW(core::pyr_up(s, 5, 7));
}

}  // namespace
}  // namespace vkfuse

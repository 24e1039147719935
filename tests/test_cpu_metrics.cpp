// metrics_reference() against numpy (np.gradient etc.) on random images and
// the real DIGIT background frame (tests/data/peers/metrics.bin).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <regex>
#include <string>

#include "core/compensated_sum.hpp"
#include "peer_file.hpp"
#include "test_support.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse {
namespace {

const test::PeerFile& peers() {
    static const test::PeerFile file("metrics.bin");
    return file;
}

double check(const ImageD& img, const ImageD& bg, const test::PeerArray& ref, const std::string& what) {
    const Metrics m = metrics_reference(img, &bg);
    EXPECT_NEAR(m.sharpness, ref.values[0], 1e-6) << what;
    EXPECT_NEAR(m.contrast, ref.values[1], 1e-6) << what;
    EXPECT_TRUE(m.background_diff.has_value());
    EXPECT_NEAR(*m.background_diff, ref.values[2], 1e-6) << what;
    return std::max({std::abs(m.sharpness - ref.values[0]), std::abs(m.contrast - ref.values[1]),
                     std::abs(*m.background_diff - ref.values[2])});
}

TEST(CpuMetrics, RandomImagesMatchNumpy) {
    const std::regex key(R"((\d+x\d+x\d+)/metrics)");
    double worst = 0;
    int cases = 0;
    for (const auto& [name, array] : peers().all()) {
        std::smatch m;
        if (!std::regex_match(name, m, key)) continue;
        const std::string base = m[1].str();
        worst = std::max(worst, check(peers().image(base + "/image"), peers().image(base + "/background"), array,
                                      name));
        ++cases;
    }
    EXPECT_EQ(cases, 7);
    std::printf("[peer] metrics on random images: %d cases, worst |err| = %.3g\n", cases, worst);
}

TEST(CpuMetrics, DigitBackgroundMatchesNumpy) {
    ImageD rgb = peers().image("digit/rgb8");
    for (double& v : rgb.data) v /= 255.0;
    ImageD shifted(rgb.height, rgb.width, 3);  // np.roll(rgb, (3, -2), axis=(0, 1))
    for (int y = 0; y < rgb.height; ++y)
        for (int x = 0; x < rgb.width; ++x)
            for (int c = 0; c < 3; ++c)
                shifted.at((y + 3) % rgb.height, (x - 2 + rgb.width) % rgb.width, c) = rgb.at(y, x, c);
    const double err = check(rgb, shifted, peers().at("digit/metrics_vs_shifted"), "digit");
    std::printf("[peer] metrics on digit_bg_tacto.png: worst |err| = %.3g\n", err);
}

TEST(CpuMetrics, ConstantImageHasNoSharpnessNoContrast) {
    for (int c : {1, 3}) {
        ImageD img(17, 23, c);
        for (double& v : img.data) v = 0.4;
        const Metrics m = metrics_reference(img);
        EXPECT_EQ(m.sharpness, 0.0);
        EXPECT_NEAR(m.contrast, 0.0, 1e-15);
        EXPECT_FALSE(m.background_diff.has_value());
        EXPECT_NEAR(*metrics_reference(img, &img).background_diff, 0.0, 0.0);
    }
}

TEST(CpuMetrics, HandComputedValues) {
    // Y = [[0, 1, 3]]: gx = [1, 1.5, 2], gy = 0 (one row) -> sharpness 1.5;
    // mean 4/3, population variance (16/9 + 1/9 + 25/9) / 3 = 14/9.
    ImageD img(1, 3, 1);
    img.data = {0.0, 1.0, 3.0};
    const Metrics m = metrics_reference(img);
    EXPECT_DOUBLE_EQ(m.sharpness, 1.5);
    EXPECT_DOUBLE_EQ(m.contrast, std::sqrt(14.0 / 9.0));
    ImageD rgb(1, 1, 3);
    rgb.data = {1.0, 0.0, 0.0};
    ImageD black(1, 1, 3);
    EXPECT_DOUBLE_EQ(*metrics_reference(rgb, &black).background_diff, 1.0 / 3.0);
}

TEST(CpuMetrics, BackgroundOfAnotherShapeIsAShapeError) {
    const ImageD img = test::random_image(5, 6, 3, 1), bg = test::random_image(6, 5, 3, 2);
    try {
        metrics_reference(img, &bg);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Shape);
    }
}

TEST(CpuMetrics, CompensatedSumKeepsFullPrecisionOverManyTerms) {
    // 0.1 is not exact in binary; ten million naive additions drift by ~1e-4.
    core::CompensatedSum sum;
    double naive = 0;
    for (int i = 0; i < 10'000'000; ++i) {
        sum.add(0.1);
        naive += 0.1;
    }
    EXPECT_NEAR(sum.value(), 1e6, 1e-9);
    EXPECT_GT(std::abs(naive - 1e6), 1e-6);  // the naive sum really is worse
}

TEST(CpuMetrics, MetricListsParseAndPrint) {
    for (unsigned bits = 1; bits < 8; ++bits) {
        MetricSet which;
        for (Metric m : kAllMetrics) which = which.with(m, (bits >> unsigned(m)) & 1u);
        EXPECT_EQ(MetricSet::parse(which.to_string()), which) << which.to_string();
    }
    EXPECT_EQ(MetricSet::parse("contrast,sharpness"), (MetricSet{Metric::Sharpness, Metric::Contrast}));
    EXPECT_EQ(MetricSet::all().to_string(), "sharpness,contrast,background_diff");
    for (const char* bad : {"", ",", "sharpness,", "sharpness,sharpness", "Sharpness", "contrast;sharpness", "all"})
        EXPECT_FALSE(MetricSet::parse(bad).has_value()) << bad;
    EXPECT_TRUE(MetricSet{}.empty());
}

}  // namespace
}  // namespace vkfuse

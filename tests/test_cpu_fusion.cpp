// fuse_reference() against docs/spec.md computed in numpy/pywt/cv2
// (tests/data/peers/fusion.bin), plus the invariants every method must keep.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include "peer_file.hpp"
#include "test_support.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse {
namespace {

constexpr double kPeerTolerance = 1e-6;

const test::PeerFile& peers() {
    static const test::PeerFile file("fusion.bin");
    return file;
}

// Compares fuse_reference with one stored result; returns the error.
double check(const std::vector<ImageD>& frames, const FusionSpec& spec, const std::string& key) {
    const ImageD fused = fuse_reference(frames, spec);
    const double err = test::max_abs_diff(fused, peers().image(key));
    EXPECT_LE(err, kPeerTolerance) << key;
    return err;
}

FusionSpec spec_of(Method m, int levels = 0) {
    FusionSpec s;
    s.method = m;
    s.levels = levels;
    return s;
}

TEST(CpuFusion, EveryRulePairMatchesPeersForWaveletAndLaplacian) {
    const std::vector<ImageD> frames = peers().frames("rules/frames");
    const char* rules[] = {"max-abs", "mean", "max", "min"};
    double worst_wavelet = 0, worst_laplacian = 0;
    for (const char* base : rules)
        for (const char* detail : rules) {
            FusionSpec s = spec_of(Method::Wavelet, 2);
            s.wavelet = Wavelet::Bior44;
            s.base_rule = parse_rule(base);
            s.detail_rule = parse_rule(detail);
            const std::string tail = std::string(base) + "/" + detail;
            worst_wavelet = std::max(worst_wavelet, check(frames, s, "rules/wavelet/bior4.4/L2/" + tail));
            s.method = Method::Laplacian;
            s.levels = 4;
            worst_laplacian = std::max(worst_laplacian, check(frames, s, "rules/laplacian/L4/" + tail));
        }
    std::printf("[peer] wavelet fusion, 16 rule pairs: worst |err| = %.3g\n", worst_wavelet);
    std::printf("[peer] laplacian fusion, 16 rule pairs: worst |err| = %.3g\n", worst_laplacian);
}

TEST(CpuFusion, EveryWaveletMatchesPeersOnRgb) {
    const std::vector<ImageD> frames = peers().frames("wavelet/29x38x3/frames");
    const std::regex key(R"(wavelet/29x38x3/([^/]+)/L(\d+))");
    double worst = 0;
    int cases = 0;
    for (const auto& [name, array] : peers().all()) {
        std::smatch m;
        if (!std::regex_match(name, m, key)) continue;
        FusionSpec s = spec_of(Method::Wavelet, std::stoi(m[2]));
        s.wavelet = parse_wavelet(m[1].str());
        worst = std::max(worst, check(frames, s, name));
        ++cases;
    }
    EXPECT_EQ(cases, 7);  // bior4.4 carries a single level at 29 rows
    std::printf("[peer] wavelet fusion RGB, every wavelet: %d cases, worst |err| = %.3g\n", cases, worst);
}

TEST(CpuFusion, LaplacianMatchesPeersAtOddAndTinySizes) {
    const std::regex key(R"((laplacian/L(\d+)/[0-9x]+)/fused)");
    double worst = 0;
    int cases = 0;
    for (const auto& [name, array] : peers().all()) {
        std::smatch m;
        if (!std::regex_match(name, m, key)) continue;
        worst = std::max(worst, check(peers().frames(m[1].str() + "/frames"), spec_of(Method::Laplacian,
                                                                                      std::stoi(m[2])), name));
        ++cases;
    }
    EXPECT_EQ(cases, 5);
    std::printf("[peer] laplacian fusion sizes: %d cases, worst |err| = %.3g\n", cases, worst);
}

TEST(CpuFusion, BroveyAndChannelSumMatchPeers) {
    double worst = 0;
    for (const char* key : {"brovey/19x23x3", "brovey/7x5x1"})
        worst = std::max(worst, check(peers().frames(std::string(key) + "/frames"), spec_of(Method::Brovey),
                                      std::string(key) + "/fused"));
    const std::vector<ImageD> rgb = peers().frames("channel-sum/9x7x3/frames");
    const ImageD fused = fuse_reference(rgb, spec_of(Method::ChannelSum));
    EXPECT_EQ(test::max_abs_diff(fused, peers().image("channel-sum/9x7x3/fused")), 0.0);
    std::printf("[peer] brovey: worst |err| = %.3g\n", worst);
}

TEST(CpuFusion, DefaultLevelsAreLaplacianFourWaveletThree) {
    EXPECT_EQ(spec_of(Method::Laplacian).effective_levels(), 4);
    EXPECT_EQ(spec_of(Method::Wavelet).effective_levels(), 3);
    EXPECT_EQ(spec_of(Method::Brovey).effective_levels(), 0);
    EXPECT_EQ(spec_of(Method::Wavelet, 2).effective_levels(), 2);
}

// Fusing K copies of one frame must give the frame back: every rule returns
// the common value and every transform reconstructs perfectly. Except that
// pywt's tabulated bior4.4 filters are biorthogonal only to ~5e-13, so its
// periodization round trip is off by ~2e-12 (pywt's own waverec2(wavedec2(x))
// shows the same); the lifting (symmetric) mode uses exact constants.
TEST(CpuFusion, IdenticalFramesFuseToThemselves) {
    const Rule rules[] = {Rule::MaxAbs, Rule::Mean, Rule::Max, Rule::Min};
    const Wavelet wavelets[] = {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44};
    const ImageD img = test::structured_image(45, 38, 3, 11);
    const std::vector<ImageD> frames(3, img);
    double worst = 0;
    auto expect_identity = [&](const FusionSpec& s, const std::string& what) {
        const double err = test::max_abs_diff(fuse_reference(frames, s), img);
        const bool tabulated_97 = s.method == Method::Wavelet && s.wavelet == Wavelet::Bior44 &&
                                  s.mode == WaveletMode::Periodization;
        EXPECT_LE(err, tabulated_97 ? 1e-11 : 1e-13) << what;
        worst = std::max(worst, err);
    };
    for (Rule base : rules)
        for (Rule detail : rules) {
            FusionSpec s = spec_of(Method::Laplacian);
            s.base_rule = base;
            s.detail_rule = detail;
            expect_identity(s, "laplacian");
            for (Wavelet w : wavelets)
                for (WaveletMode mode : {WaveletMode::Periodization, WaveletMode::Symmetric}) {
                    s.method = Method::Wavelet;
                    s.wavelet = w;
                    s.mode = mode;
                    s.levels = max_wavelet_levels(w, img.height, img.width);
                    expect_identity(s, std::string(to_string(w)) + " " + std::string(to_string(mode)));
                }
        }
    expect_identity(spec_of(Method::Brovey), "brovey");
    std::printf("[self] identical frames fuse to themselves: worst |err| = %.3g\n", worst);
}

TEST(CpuFusion, MismatchedFrameShapesNameTheFrame) {
    const std::vector<ImageD> frames{test::random_image(8, 9, 3, 1), test::random_image(8, 9, 3, 2),
                                     test::random_image(8, 10, 3, 3)};
    try {
        fuse_reference(frames, spec_of(Method::Brovey));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Shape);
        EXPECT_NE(std::string(e.what()).find("frame 3"), std::string::npos) << e.what();
    }
}

TEST(CpuFusion, NonFiniteInputIsANumericError) {
    std::vector<ImageD> frames{test::random_image(8, 9, 1, 1), test::random_image(8, 9, 1, 2)};
    frames[1].at(2, 3, 0) = std::numeric_limits<double>::quiet_NaN();
    try {
        fuse_reference(frames, spec_of(Method::Laplacian));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Numeric);
        EXPECT_EQ(std::string(e.what()), "frame 2: NaN at row 2, column 3, channel 0");
    }
}

TEST(CpuFusion, ChannelSumNeedsThreeRgbFrames) {
    const std::vector<ImageD> two(2, test::random_image(4, 4, 3, 1));
    EXPECT_THROW(fuse_reference(two, spec_of(Method::ChannelSum)), Error);
    const std::vector<ImageD> gray(3, test::random_image(4, 4, 1, 1));
    EXPECT_THROW(fuse_reference(gray, spec_of(Method::ChannelSum)), Error);
    EXPECT_THROW(fuse_reference(std::vector<ImageD>{}, spec_of(Method::Brovey)), Error);
}

TEST(CpuFusion, LaplacianWorksAtEveryTinySize) {
    for (int h = 1; h <= 6; ++h)
        for (int w = 1; w <= 6; ++w) {
            const std::vector<ImageD> frames{test::random_image(h, w, 1, 5), test::random_image(h, w, 1, 6)};
            const ImageD fused = fuse_reference(frames, spec_of(Method::Laplacian, 6));
            EXPECT_EQ(fused.height, h);
            EXPECT_EQ(fused.width, w);
        }
}

}  // namespace
}  // namespace vkfuse

// `vkfuse fuse --backend cpu` end to end: what it writes is fuse_reference of
// what it read, for every method and for PNG and .npy on both sides.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_runner.hpp"
#include "test_support.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

struct FuseCase {
    friend void PrintTo(const FuseCase& c, std::ostream* os) { *os << c.name; }
    std::string name;
    std::vector<std::string> options;  // without -o and inputs
    FusionSpec spec;                   // what those options mean
    int frames, height, width, channels;
};

FusionSpec spec_of(Method m, int levels = 0, Wavelet w = Wavelet::Bior44, WaveletMode mode = WaveletMode::Periodization,
                   Rule base = Rule::Mean, Rule detail = Rule::MaxAbs) {
    FusionSpec s;
    s.method = m;
    s.levels = levels;
    s.wavelet = w;
    s.mode = mode;
    s.base_rule = base;
    s.detail_rule = detail;
    return s;
}

std::vector<FuseCase> fuse_cases() {
    return {
        {"brovey", {"--method", "brovey"}, spec_of(Method::Brovey), 2, 21, 17, 3},
        {"channel_sum", {"--method", "channel-sum"}, spec_of(Method::ChannelSum), 3, 12, 9, 3},
        {"laplacian_default", {"--method", "laplacian"}, spec_of(Method::Laplacian), 2, 37, 29, 3},
        {"laplacian_gray", {"--method=laplacian", "--levels=2", "--base-rule", "max"},
         spec_of(Method::Laplacian, 2, Wavelet::Bior44, WaveletMode::Periodization, Rule::Max), 3, 19, 23, 1},
        {"wavelet_default", {"--method", "wavelet"}, spec_of(Method::Wavelet), 2, 80, 72, 3},
        {"wavelet_symmetric",
         {"--method", "wavelet", "--wavelet", "bior2.2", "--mode", "symmetric", "--levels", "2"},
         spec_of(Method::Wavelet, 2, Wavelet::Bior22, WaveletMode::Symmetric), 2, 31, 27, 3},
        {"wavelet_haar_rules",
         {"--method", "wavelet", "--wavelet", "haar", "--levels", "3", "--base-rule", "max-abs", "--detail-rule", "min"},
         spec_of(Method::Wavelet, 3, Wavelet::Haar, WaveletMode::Periodization, Rule::MaxAbs, Rule::Min), 4, 32, 24, 1},
        {"wavelet_db2", {"--method", "wavelet", "--wavelet", "db2", "--levels", "2", "--detail-rule", "max"},
         spec_of(Method::Wavelet, 2, Wavelet::Db2, WaveletMode::Periodization, Rule::Mean, Rule::Max), 2, 24, 40, 3},
    };
}

// Writes the case's frames as .npy and returns their paths and contents.
std::vector<std::string> write_frames(const TempDir& dir, const FuseCase& c, std::vector<ImageD>& frames) {
    std::vector<std::string> paths;
    for (int k = 0; k < c.frames; ++k) {
        frames.push_back(structured_image(c.height, c.width, c.channels, 100 + k));
        paths.push_back(dir.file("frame" + std::to_string(k) + ".npy"));
        io::write_image(paths.back(), convert<float>(frames.back()));
    }
    return paths;
}

class CliFuse : public ::testing::TestWithParam<FuseCase> {};

TEST_P(CliFuse, CpuBackendWritesTheReferenceFusion) {
    const FuseCase& c = GetParam();
    TempDir dir;
    std::vector<ImageD> frames;
    std::vector<std::string> args = write_frames(dir, c, frames);
    std::string out = dir.file("fused.npy");
    args.insert(args.begin(), c.options.begin(), c.options.end());
    args.insert(args.begin(), "fuse");
    args.insert(args.end(), {"--backend", "cpu", "-o", out});
    CliResult r = run_cli(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "");
    Image fused = io::read_image(out);
    ImageD expected = fuse_reference(frames, c.spec);
    ASSERT_TRUE(fused.same_shape(convert<float>(expected)));
    EXPECT_LE(max_abs_diff(fused, expected), 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Methods, CliFuse, ::testing::ValuesIn(fuse_cases()),
                         [](const auto& info) { return info.param.name; });

TEST(CliFuseFormats, PngInPngOut) {
    TempDir dir;
    std::vector<ImageD> frames;
    std::vector<std::string> paths;
    for (int k = 0; k < 2; ++k) {
        paths.push_back(dir.file("f" + std::to_string(k) + ".png"));
        io::write_image(paths.back(), convert<float>(structured_image(30, 20, 3, 7 + k)));
        frames.push_back(convert<double>(io::read_image(paths.back())));  // what the 8-bit file holds
    }
    std::string out = dir.file("fused.png");
    CliResult r = run_cli({"fuse", "--method", "laplacian", "--backend", "cpu", "-o", out, paths[0], paths[1]});
    ASSERT_EQ(r.status, 0) << r.err;
    Image fused = io::read_image(out);
    ImageD expected = fuse_reference(frames, spec_of(Method::Laplacian));
    for (double& v : expected.data) v = std::round(std::clamp(v, 0.0, 1.0) * 255.0) / 255.0;
    // A value within float rounding of a .5 step may land on either side.
    EXPECT_LE(max_abs_diff(fused, expected), 1.0 / 255 + 1e-6);
}

TEST(CliFuseFormats, OptionsMayFollowOperands) {
    TempDir dir;
    FuseCase c{"late", {}, spec_of(Method::Brovey), 2, 8, 8, 1};
    std::vector<ImageD> frames;
    std::vector<std::string> paths = write_frames(dir, c, frames);
    CliResult r = run_cli({"fuse", paths[0], "--output", dir.file("o.npy"), paths[1], "--backend=cpu", "--method",
                           "brovey"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_LE(max_abs_diff(io::read_image(dir.file("o.npy")), fuse_reference(frames, c.spec)), 1e-6);
}

// auto works whether or not a Vulkan device exists; without one it says so in one line.
TEST(CliFuseBackends, AutoMatchesTheCpuPath) {
    TempDir dir;
    FuseCase c{"auto", {}, spec_of(Method::Wavelet, 2), 2, 40, 36, 3};
    std::vector<ImageD> frames;
    std::vector<std::string> paths = write_frames(dir, c, frames);
    CliResult r = run_cli({"fuse", "--method", "wavelet", "--levels", "2", "-o", dir.file("o.npy"), paths[0], paths[1]});
    ASSERT_EQ(r.status, 0) << r.err;
    for (const std::string& line : r.err_lines())
        EXPECT_NE(line.find("no usable Vulkan device"), std::string::npos) << line;
    EXPECT_LE(r.err_lines().size(), 1u);
    EXPECT_LE(max_abs_diff(io::read_image(dir.file("o.npy")), fuse_reference(frames, c.spec)), 1e-5);
}

}  // namespace
}  // namespace vkfuse::test

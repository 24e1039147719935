// `--backend vulkan` end to end: the GPU path must agree with the CPU path
// (docs/spec.md tolerances: fused 1e-5 absolute, metrics 1e-5 relative). Needs a
// Vulkan device (lavapipe in CI). Runs with the validation layer on
// with synchronization validation (VKFUSE_VALIDATION=sync): any message lands
// on stderr, which must stay empty.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "cli_runner.hpp"
#include "test_support.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

const std::vector<std::string> kValidation{"VKFUSE_VALIDATION=sync"};

struct VkCase {
    std::string name;
    std::vector<std::string> options;
    int frames, height, width, channels;
    friend void PrintTo(const VkCase& c, std::ostream* os) { *os << c.name; }
};

std::vector<VkCase> vk_cases() {
    return {
        {"brovey", {"--method", "brovey"}, 3, 45, 38, 3},
        {"channel_sum", {"--method", "channel-sum"}, 3, 20, 31, 3},
        {"laplacian", {"--method", "laplacian"}, 2, 61, 97, 3},
        {"laplacian_gray_max", {"--method", "laplacian", "--levels", "3", "--base-rule", "max"}, 3, 33, 47, 1},
        {"wavelet_default", {"--method", "wavelet"}, 2, 96, 80, 3},
        {"wavelet_symmetric", {"--method", "wavelet", "--mode", "symmetric", "--wavelet", "bior2.2", "--levels", "2"},
         2, 37, 29, 3},
        {"wavelet_haar_min", {"--method", "wavelet", "--wavelet", "haar", "--levels", "4", "--detail-rule", "min"}, 3,
         64, 48, 1},
        {"wavelet_db2_mean", {"--method", "wavelet", "--wavelet", "db2", "--levels", "2", "--detail-rule", "mean"}, 2,
         40, 44, 3},
    };
}

// Runs the same command on one backend; the output file is returned.
Image fuse_with(const TempDir& dir, const VkCase& c, const std::vector<std::string>& inputs, const std::string& backend) {
    std::string out = dir.file(backend + ".npy");
    std::vector<std::string> args{"fuse", "--backend", backend, "-o", out};
    args.insert(args.end(), c.options.begin(), c.options.end());
    args.insert(args.end(), inputs.begin(), inputs.end());
    CliResult r = run_cli(args, kValidation);
    EXPECT_EQ(r.status, 0) << backend << ": " << r.err;
    EXPECT_EQ(r.err, "");
    return r.status == 0 ? io::read_image(out) : Image();
}

class CliVulkanFuse : public ::testing::TestWithParam<VkCase> {};

TEST_P(CliVulkanFuse, MatchesTheCpuBackend) {
    const VkCase& c = GetParam();
    TempDir dir;
    std::vector<std::string> inputs;
    for (int k = 0; k < c.frames; ++k) {
        inputs.push_back(dir.file("in" + std::to_string(k) + ".npy"));
        io::write_image(inputs.back(), convert<float>(structured_image(c.height, c.width, c.channels, 40 + k)));
    }
    Image cpu = fuse_with(dir, c, inputs, "cpu");
    Image gpu = fuse_with(dir, c, inputs, "vulkan");
    ASSERT_TRUE(gpu.same_shape(cpu));
    EXPECT_LE(max_abs_diff(gpu, convert<double>(cpu)), 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Methods, CliVulkanFuse, ::testing::ValuesIn(vk_cases()),
                         [](const auto& info) { return info.param.name; });

std::vector<double> numbers_in(const std::string& text) {
    std::vector<double> values;
    for (std::size_t at = 0; (at = text.find("\": ", at)) != std::string::npos; at += 3) {
        const char* start = text.c_str() + at + 3;
        char* end = nullptr;
        double v = std::strtod(start, &end);
        if (end != start) values.push_back(v);
    }
    return values;
}

void expect_metrics_agree(const std::vector<std::string>& args) {
    std::vector<std::string> cpu_args{"metrics", "--backend", "cpu"}, gpu_args{"metrics", "--backend", "vulkan"};
    cpu_args.insert(cpu_args.end(), args.begin(), args.end());
    gpu_args.insert(gpu_args.end(), args.begin(), args.end());
    CliResult cpu = run_cli(cpu_args), gpu = run_cli(gpu_args, kValidation);
    ASSERT_EQ(cpu.status, 0) << cpu.err;
    ASSERT_EQ(gpu.status, 0) << gpu.err;
    EXPECT_EQ(gpu.err, "");
    std::vector<double> want = numbers_in(cpu.out), got = numbers_in(gpu.out);
    ASSERT_EQ(got.size(), want.size()) << gpu.out;
    for (std::size_t i = 0; i < want.size(); ++i)
        EXPECT_LE(std::abs(got[i] - want[i]), 1e-5 * std::abs(want[i])) << i << ": " << got[i] << " vs " << want[i];
}

TEST(CliVulkanMetrics, MatchesTheCpuBackendAcrossShapes) {
    TempDir dir;
    std::vector<std::string> paths{dir.file("a.npy"), dir.file("b.npy"), dir.file("c.npy"), dir.file("d.npy")};
    io::write_image(paths[0], convert<float>(structured_image(120, 90, 3, 1)));
    io::write_image(paths[1], convert<float>(random_image(33, 7, 1, 2)));
    io::write_image(paths[2], convert<float>(structured_image(120, 90, 3, 3)));  // same plan as a
    io::write_image(paths[3], convert<float>(structured_image(1, 64, 3, 4)));    // a single row
    expect_metrics_agree(paths);
}

TEST(CliVulkanMetrics, BackgroundDifferenceOnTheRealFrame) {
    TempDir dir;
    std::string bg = data_path("digit_bg_tacto.png");
    Image touched = io::read_image(bg);
    for (int y = 150; y < 210; ++y)
        for (int x = 60; x < 160; ++x) touched.at(y, x, 0) = std::min(1.0f, touched.at(y, x, 0) + 0.3f);
    io::write_image(dir.file("touch.npy"), touched);
    expect_metrics_agree({"--background", bg, dir.file("touch.npy"), bg});
}

}  // namespace
}  // namespace vkfuse::test

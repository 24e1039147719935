// The CLI on a machine without a usable Vulkan driver, simulated by pointing
// the loader at a driver manifest that does not exist.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "test_support.hpp"
#include "vkfuse/io.hpp"
#include "vkfuse/reference.hpp"

namespace vkfuse::test {
namespace {

// VK_DRIVER_FILES for current loaders, VK_ICD_FILENAMES for older ones.
const std::vector<std::string> kNoDriver{"VK_DRIVER_FILES=/nonexistent/vkfuse-test-icd.json",
                                         "VK_ICD_FILENAMES=/nonexistent/vkfuse-test-icd.json"};

std::vector<std::string> write_frames(const TempDir& dir) {
    std::vector<std::string> paths{dir.file("a.npy"), dir.file("b.npy")};
    for (std::size_t k = 0; k < paths.size(); ++k)
        io::write_image(paths[k], convert<float>(structured_image(24, 20, 3, 60 + std::uint32_t(k))));
    return paths;
}

TEST(CliNoDevice, BackendVulkanFailsWithOneLineAndNoOutput) {
    TempDir dir;
    std::vector<std::string> in = write_frames(dir);
    std::vector<std::string> before = dir.entries();
    CliResult r = run_cli({"fuse", "--backend", "vulkan", "--method", "brovey", "-o", dir.file("o.npy"), in[0], in[1]},
                          kNoDriver);
    EXPECT_EQ(r.status, 2);
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("vkfuse: --backend vulkan: no usable Vulkan device (", 0), 0u) << r.err;
    EXPECT_EQ(dir.entries(), before);
    CliResult m = run_cli({"metrics", "--backend", "vulkan", in[0]}, kNoDriver);
    EXPECT_EQ(m.status, 2);
    EXPECT_EQ(m.out, "");
}

TEST(CliNoDevice, AutoFallsBackToTheCpuAndSaysSoOnce) {
    TempDir dir;
    std::vector<std::string> in = write_frames(dir);
    CliResult r = run_cli({"fuse", "--method", "laplacian", "-o", dir.file("o.npy"), in[0], in[1]}, kNoDriver);
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("vkfuse: no usable Vulkan device (", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("); using the CPU reference path\n"), std::string::npos) << r.err;
    std::vector<ImageD> frames{convert<double>(io::read_image(in[0])), convert<double>(io::read_image(in[1]))};
    FusionSpec spec;
    spec.method = Method::Laplacian;
    EXPECT_LE(max_abs_diff(io::read_image(dir.file("o.npy")), fuse_reference(frames, spec)), 1e-6);
}

TEST(CliNoDevice, InfoSaysTheCpuPathWillBeUsed) {
    CliResult r = run_cli({"info"}, kNoDriver);
    EXPECT_EQ(r.status, 0) << r.err;
    bool cpu_said = r.out.find("the CPU reference path will be used") != std::string::npos ||
                    r.out.find("--backend auto uses the CPU reference path") != std::string::npos;
    EXPECT_TRUE(cpu_said) << r.out;
}

}  // namespace
}  // namespace vkfuse::test

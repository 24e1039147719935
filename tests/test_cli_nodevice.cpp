// The CLI on a machine without a usable Vulkan driver, simulated by pointing
// the loader at a driver manifest that does not exist, and on one without a
// Vulkan loader at all: VKFUSE_VULKAN_LIBRARY naming a file that does not
// exist, or a library that is not a loader (no vkGetInstanceProcAddr), and a
// fake libvulkan.so.1 found first on LD_LIBRARY_PATH.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "cli_runner.hpp"
#include "test_support.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

// VK_DRIVER_FILES for current loaders, VK_ICD_FILENAMES for older ones.
const std::vector<std::string> kNoDriver{"VK_DRIVER_FILES=/nonexistent/vkfuse-test-icd.json",
                                         "VK_ICD_FILENAMES=/nonexistent/vkfuse-test-icd.json"};

const std::vector<std::string> kNoLoader{"VKFUSE_VULKAN_LIBRARY=/nonexistent/libvulkan.so.1"};

// The C library: loadable, present everywhere, and no Vulkan loader.
std::string not_a_loader() {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void*>(&std::fclose), &info) || !info.dli_fname)
        throw std::runtime_error("cannot find the C library");
    return info.dli_fname;
}

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

// Every way the loader can be missing gives the same one line, naming the cause.
TEST(CliNoLoader, BackendVulkanFailsWithOneLineNamingTheLoader) {
    TempDir dir;
    std::vector<std::string> in = write_frames(dir);
    std::filesystem::create_directory(dir.file("lib"));
    std::filesystem::create_symlink(not_a_loader(), dir.file("lib/libvulkan.so.1"));
    const std::vector<std::pair<std::vector<std::string>, std::string>> machines{
        {kNoLoader, "Vulkan loader /nonexistent/libvulkan.so.1 (VKFUSE_VULKAN_LIBRARY) cannot be loaded: "},
        {{"VKFUSE_VULKAN_LIBRARY=" + not_a_loader()}, "vkGetInstanceProcAddr missing from " + not_a_loader()},
        {{"LD_LIBRARY_PATH=" + dir.file("lib")}, "vkGetInstanceProcAddr missing from libvulkan.so.1"},
    };
    std::vector<std::string> before = dir.entries();
    for (const auto& [env, cause] : machines) {
        SCOPED_TRACE(env.front());
        CliResult r = run_cli({"fuse", "--backend", "vulkan", "--method", "brovey", "-o", dir.file("o.npy"), in[0], in[1]},
                              env);
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(r.out, "");
        ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
        EXPECT_EQ(r.err.rfind("vkfuse: --backend vulkan: no usable Vulkan device (", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(cause), std::string::npos) << r.err;
        EXPECT_EQ(dir.entries(), before);
    }
}

TEST(CliNoLoader, AutoFallsBackToTheCpuAndSaysSoOnce) {
    TempDir dir;
    std::vector<std::string> in = write_frames(dir);
    CliResult r = run_cli({"metrics", in[0]}, kNoLoader);
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("vkfuse: no usable Vulkan device (Vulkan loader /nonexistent/libvulkan.so.1", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("); using the CPU reference path\n"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("\"sharpness\": "), std::string::npos) << r.out;
}

TEST(CliNoLoader, InfoSaysThereIsNoLoader) {
    CliResult r = run_cli({"info"}, kNoLoader);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.rfind("No Vulkan loader (Vulkan loader /nonexistent/libvulkan.so.1", 0), 0u) << r.out;
    EXPECT_NE(r.out.find("the CPU reference path will be used"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace vkfuse::test

// The CLI when the device is lost mid-run (the test layer of tests/vk_layer
// makes lavapipe's vkWaitForFences report VK_ERROR_DEVICE_LOST): exit status
// 2, one line naming the failed call, no output file. --backend auto does not
// hide it behind the CPU path: that fallback is for a machine without a
// device, not for a device that failed while computing.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "lose_device.hpp"
#include "test_support.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

TEST(CliDeviceLost, ExitTwoWithOneLineAndNoOutput) {
    TempDir dir;
    io::write_image(dir.file("a.npy"), convert<float>(random_image(24, 20, 3, 1)));
    io::write_image(dir.file("b.npy"), convert<float>(random_image(24, 20, 3, 2)));
    const std::vector<std::string> before = dir.entries();
    for (const char* backend : {"vulkan", "auto"}) {
        SCOPED_TRACE(backend);
        CliResult r = run_cli({"fuse", "--backend", backend, "--method", "wavelet", "--wavelet", "haar", "-o",
                               dir.file("o.npy"), dir.file("a.npy"), dir.file("b.npy")},
                              lose_device_environment(0));
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(r.out, "");
        ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
        EXPECT_EQ(r.err.rfind("vkfuse: Vulkan vkWaitForFences: device lost (VK_ERROR_DEVICE_LOST)", 0), 0u) << r.err;
        EXPECT_EQ(dir.entries(), before);
    }
    CliResult m = run_cli({"metrics", "--backend", "vulkan", dir.file("a.npy")}, lose_device_environment(0));
    EXPECT_EQ(m.status, 2);
    EXPECT_EQ(m.out, "");
    EXPECT_NE(m.err.find("device lost"), std::string::npos) << m.err;
}

}  // namespace
}  // namespace vkfuse::test

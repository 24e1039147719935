// A device lost mid-run (a GPU reset, a driver crash, a hung kernel killed by
// the OS) comes back from vkQueueSubmit or vkWaitForFences as
// VK_ERROR_DEVICE_LOST. check() turns every failed result into an Error of
// kind Device with one line naming the call; lavapipe never loses its device,
// so a test layer (tests/vk_layer) makes vkWaitForFences say it did.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <optional>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "lose_device.hpp"
#include "vk/engine/api.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::test {
namespace {

TEST(VulkanErrors, FailedCallsBecomeDeviceErrorsNamingTheCall) {
    const std::vector<std::pair<VkResult, std::string>> results{
        {VK_ERROR_DEVICE_LOST, "device lost (VK_ERROR_DEVICE_LOST) (-4)"},
        {VK_ERROR_OUT_OF_DEVICE_MEMORY, "out of device memory (VK_ERROR_OUT_OF_DEVICE_MEMORY) (-2)"},
        {VK_ERROR_OUT_OF_HOST_MEMORY, "out of host memory (VK_ERROR_OUT_OF_HOST_MEMORY) (-1)"},
        {VK_TIMEOUT, "VK_TIMEOUT (2)"},
        {VkResult(-1000012345), "VkResult error (-1000012345)"},
    };
    for (const auto& [result, text] : results)
        for (const char* call : {"vkQueueSubmit", "vkWaitForFences"})
            expect_error([&] { vk::check(result, call); }, std::string("Vulkan ") + call, ErrorKind::Device, text);
}

TEST(VulkanErrors, SuccessIsNotAnError) { EXPECT_NO_THROW(vk::check(VK_SUCCESS, "vkQueueSubmit")); }

// Sets "NAME=value" entries for this process while alive (the loader reads
// them when an instance is created), restoring what was there before.
class ScopedEnvironment {
public:
    explicit ScopedEnvironment(const std::vector<std::string>& entries) {
        for (const std::string& e : entries) {
            const std::string name = e.substr(0, e.find('='));
            const char* old = ::getenv(name.c_str());
            saved_.push_back({name, old ? std::optional<std::string>(old) : std::nullopt});
            ::setenv(name.c_str(), e.substr(e.find('=') + 1).c_str(), 1);
        }
    }
    ~ScopedEnvironment() {
        for (const auto& [name, old] : saved_)
            if (old) ::setenv(name.c_str(), old->c_str(), 1);
            else ::unsetenv(name.c_str());
    }

private:
    std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

// The first cycle runs; the second loses the device: run() throws, and the
// plan and the context (which wait for the device on the way out) still close
// without hanging or crashing.
TEST(VulkanDeviceLost, RunThrowsAndEverythingStillClosesCleanly) {
    ScopedEnvironment env(lose_device_environment(1));
    Context context;
    PlanConfig cfg;
    cfg.fusion.method = Method::Laplacian;
    cfg.height = 24;
    cfg.width = 32;
    cfg.channels = 3;
    cfg.frames = 2;
    Plan plan(context, cfg);
    const Image frame(24, 32, 3);
    const std::vector<FrameView> views(2, FrameView::of(frame));
    plan.run(views);
    expect_error([&] { plan.run(views); }, "Vulkan vkWaitForFences", ErrorKind::Device,
                 "device lost (VK_ERROR_DEVICE_LOST)");
}

}  // namespace
}  // namespace vkfuse::test

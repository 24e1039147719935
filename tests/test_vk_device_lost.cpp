// A device lost mid-run (a GPU reset, a driver crash, a hung kernel killed by
// the OS) comes back from vkQueueSubmit or vkWaitForFences as
// VK_ERROR_DEVICE_LOST. lavapipe never loses its device, so this tests the
// path every such result takes: check() turns it into an Error of kind Device
// with one line naming the call, which the CLI reports with exit status 2.
#include <gtest/gtest.h>

#include "expect_error.hpp"
#include "vk/api.hpp"

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

}  // namespace
}  // namespace vkfuse::test

// lose_device.hpp - the environment that enables the test layer
// VK_LAYER_VKFUSE_lose_device (tests/vk_layer): vkWaitForFences reports
// VK_ERROR_DEVICE_LOST once `after` waits have succeeded.
#pragma once
#include <string>
#include <vector>

namespace vkfuse::test {

inline std::vector<std::string> lose_device_environment(int after) {
    return {std::string("VK_ADD_LAYER_PATH=") + VKFUSE_TEST_LAYER_DIR,
            "VK_INSTANCE_LAYERS=VK_LAYER_VKFUSE_lose_device",
            "VKFUSE_TEST_LOSE_DEVICE_AFTER=" + std::to_string(after)};
}

}  // namespace vkfuse::test

// lose_device.hpp - the environment that enables the test layer
// VK_LAYER_VKFUSE_lose_device (tests/vk_layer): vkWaitForFences reports
// VK_ERROR_DEVICE_LOST once `after` waits have succeeded.
#pragma once
#include <string>
#include <vector>

namespace vkfuse::test {

inline std::vector<std::string> lose_device_environment(int after) {
    // Appended, not a temporary's operator+: GCC 12 at -O1 warns of a
    // memcpy out of bounds (a false positive) in the latter.
    std::vector<std::string> env(3);
    env[0].append("VK_ADD_LAYER_PATH=").append(VKFUSE_TEST_LAYER_DIR);
    env[1] = "VK_INSTANCE_LAYERS=VK_LAYER_VKFUSE_lose_device";
    env[2].append("VKFUSE_TEST_LOSE_DEVICE_AFTER=").append(std::to_string(after));
    return env;
}

}  // namespace vkfuse::test

// Enumerating physical devices and judging whether vkfuse can use them.
#pragma once
#include <string>
#include <vector>

#include "vk/engine/api.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::vk {

struct PhysicalDeviceEntry {
    VkPhysicalDevice handle = VK_NULL_HANDLE;
    DeviceInfo info;
    int rank = 0;  // higher is preferred: discrete > integrated > virtual > cpu
    bool memory_budget = false;  // VK_EXT_memory_budget (Context::memory_heaps)
    bool denorm_preserve = false;  // shaderDenormPreserveFloat32: kernels may ask to keep subnormals
};

std::string version_string(std::uint32_t version);
std::vector<PhysicalDeviceEntry> enumerate_devices(const Api& api, VkInstance instance);
// The best usable device, or nullptr.
const PhysicalDeviceEntry* best_device(const std::vector<PhysicalDeviceEntry>& devices);

}  // namespace vkfuse::vk

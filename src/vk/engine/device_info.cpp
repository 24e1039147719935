#include "vk/engine/device_info.hpp"

#include <cstring>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

const char* type_name(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        default: return "other";
    }
}

int type_rank(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
        default: return 0;
    }
}

PhysicalDeviceEntry describe(const Api& api, VkPhysicalDevice dev, int index) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceFloatControlsProperties float_controls{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    VkPhysicalDeviceProperties basic{};
    api.vkGetPhysicalDeviceProperties(dev, &basic);
    const bool is12 = basic.apiVersion >= VK_API_VERSION_1_2;
    if (is12) {
        props.pNext = &driver;
        driver.pNext = &float_controls;
        api.vkGetPhysicalDeviceProperties2(dev, &props);
    }
    PhysicalDeviceEntry e;
    e.handle = dev;
    e.info.index = index;
    e.info.name = basic.deviceName;
    e.info.driver = is12 ? std::string(driver.driverName) + " " + driver.driverInfo : "unknown";
    e.info.type = type_name(basic.deviceType);
    e.info.api_version = version_string(basic.apiVersion);
    e.rank = type_rank(basic.deviceType);
    if (!is12) {
        e.info.why_not = "Vulkan " + e.info.api_version + " < 1.2";
        return e;
    }
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f.pNext = &f12;
    f12.pNext = &f11;
    api.vkGetPhysicalDeviceFeatures2(dev, &f);
    e.info.device_addresses = f12.bufferDeviceAddress;
    e.info.fp16_storage = f11.storageBuffer16BitAccess;  // storage only: no module needs shaderFloat16
    e.info.float64 = f.features.shaderFloat64;
    e.denorm_preserve = float_controls.shaderDenormPreserveFloat32;
    e.info.float32_subnormals = e.denorm_preserve || basic.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    std::uint32_t n = 0;
    api.vkEnumerateDeviceExtensionProperties(dev, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> extensions(n);
    api.vkEnumerateDeviceExtensionProperties(dev, nullptr, &n, extensions.data());
    for (const auto& x : extensions) {
        if (std::strcmp(x.extensionName, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME) == 0) e.info.external_memory_fd = true;
        if (std::strcmp(x.extensionName, VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME) == 0) e.info.external_memory_host = true;
        if (std::strcmp(x.extensionName, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME) == 0) e.memory_budget = true;
    }
    e.info.usable = true;
    return e;
}

}  // namespace

std::string version_string(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

std::vector<PhysicalDeviceEntry> enumerate_devices(const Api& api, VkInstance instance) {
    std::uint32_t n = 0;
    VkResult r = api.vkEnumeratePhysicalDevices(instance, &n, nullptr);
    if (r == VK_ERROR_INITIALIZATION_FAILED) return {};
    check(r, "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> handles(n);
    check(api.vkEnumeratePhysicalDevices(instance, &n, handles.data()), "vkEnumeratePhysicalDevices");
    std::vector<PhysicalDeviceEntry> out;
    for (std::uint32_t i = 0; i < n; ++i) out.push_back(describe(api, handles[i], int(i)));
    return out;
}

const PhysicalDeviceEntry* best_device(const std::vector<PhysicalDeviceEntry>& devices) {
    const PhysicalDeviceEntry* best = nullptr;
    for (auto& d : devices)
        if (d.info.usable && (!best || d.rank > best->rank)) best = &d;
    return best;
}

}  // namespace vkfuse::vk

namespace vkfuse {

std::vector<DeviceInfo> list_devices() {
    auto api = vk::Api::load();
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    VkResult r = api->vkCreateInstance(&ci, nullptr, &instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER) return {};
    vk::check(r, "vkCreateInstance");
    std::vector<DeviceInfo> out;
    try {
        api->load_instance(instance);
        for (auto& e : vk::enumerate_devices(*api, instance)) out.push_back(e.info);
    } catch (...) {
        if (api->vkDestroyInstance) api->vkDestroyInstance(instance, nullptr);
        throw;
    }
    api->vkDestroyInstance(instance, nullptr);
    return out;
}

}  // namespace vkfuse

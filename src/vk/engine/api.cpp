#include "vk/engine/api.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <string>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

namespace {

// The loader library: VKFUSE_VULKAN_LIBRARY when set (a loader outside the
// library path, or a test pointing it at nothing to be a machine without
// Vulkan), the only one tried then; else the system's libvulkan.so.1.
void* open_loader(std::string& name) {
    if (const char* chosen = std::getenv("VKFUSE_VULKAN_LIBRARY"); chosen && *chosen) {
        name = chosen;
        void* lib = dlopen(chosen, RTLD_NOW | RTLD_LOCAL);
        if (!lib) {
            const char* why = dlerror();
            throw Error(ErrorKind::Device, "Vulkan loader " + name + " (VKFUSE_VULKAN_LIBRARY) cannot be loaded: " +
                                               (why ? why : "unknown dlopen error"));
        }
        return lib;
    }
    name = "libvulkan.so.1";
    void* lib = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) lib = dlopen("libvulkan.so", RTLD_NOW | RTLD_LOCAL);
    if (!lib) throw Error(ErrorKind::Device, "Vulkan loader libvulkan.so.1 not found (install libvulkan1)");
    return lib;
}

}  // namespace

std::unique_ptr<Api> Api::load() {
    std::string name;
    void* lib = open_loader(name);
    auto api = std::make_unique<Api>();
    api->library_ = lib;
    api->vkGetInstanceProcAddr = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(lib, "vkGetInstanceProcAddr"));
    if (!api->vkGetInstanceProcAddr)
        throw Error(ErrorKind::Device, "Vulkan loader: vkGetInstanceProcAddr missing from " + name);
    api->load_global();
    return api;
}

std::unique_ptr<Api> Api::adopt(PFN_vkGetInstanceProcAddr get_instance_proc_addr) {
    if (!get_instance_proc_addr) return load();
    auto api = std::make_unique<Api>();
    api->vkGetInstanceProcAddr = get_instance_proc_addr;
    api->load_global();
    return api;
}

void Api::load_global() {
    Api* api = this;
#define VKFUSE_LOAD_GLOBAL(name) api->name = reinterpret_cast<PFN_##name>(api->vkGetInstanceProcAddr(nullptr, #name));
    VKFUSE_GLOBAL_FUNCS(VKFUSE_LOAD_GLOBAL)
#undef VKFUSE_LOAD_GLOBAL
    if (!api->vkCreateInstance) throw Error(ErrorKind::Device, "Vulkan loader: vkCreateInstance unavailable");
}

void Api::load_instance(VkInstance instance) {
#define VKFUSE_LOAD_INSTANCE(name)                                                              \
    name = reinterpret_cast<PFN_##name>(vkGetInstanceProcAddr(instance, #name));               \
    if (!name) throw Error(ErrorKind::Device, "Vulkan instance lacks " #name);
    VKFUSE_INSTANCE_FUNCS(VKFUSE_LOAD_INSTANCE)
#undef VKFUSE_LOAD_INSTANCE
    // Debug utils exist only when the extension was enabled; null otherwise.
#define VKFUSE_LOAD_OPTIONAL(name) name = reinterpret_cast<PFN_##name>(vkGetInstanceProcAddr(instance, #name));
    VKFUSE_DEBUG_FUNCS(VKFUSE_LOAD_OPTIONAL)
#undef VKFUSE_LOAD_OPTIONAL
}

void Api::load_device(VkDevice device) {
#define VKFUSE_LOAD_DEVICE(name)                                                                \
    name = reinterpret_cast<PFN_##name>(vkGetDeviceProcAddr(device, #name));                    \
    if (!name) throw Error(ErrorKind::Device, "Vulkan device lacks " #name);
    VKFUSE_DEVICE_FUNCS(VKFUSE_LOAD_DEVICE)
#undef VKFUSE_LOAD_DEVICE
#define VKFUSE_LOAD_DEVICE_OPTIONAL(name) name = reinterpret_cast<PFN_##name>(vkGetDeviceProcAddr(device, #name));
    VKFUSE_DEVICE_OPTIONAL_FUNCS(VKFUSE_LOAD_DEVICE_OPTIONAL)
#undef VKFUSE_LOAD_DEVICE_OPTIONAL
}

Api::~Api() {
    if (library_) dlclose(library_);
}

const char* result_name(VkResult r) {
    switch (r) {
        case VK_SUCCESS: return "VK_SUCCESS";
        case VK_NOT_READY: return "VK_NOT_READY";
        case VK_TIMEOUT: return "VK_TIMEOUT";
        case VK_ERROR_OUT_OF_HOST_MEMORY: return "out of host memory (VK_ERROR_OUT_OF_HOST_MEMORY)";
        case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "out of device memory (VK_ERROR_OUT_OF_DEVICE_MEMORY)";
        case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
        case VK_ERROR_DEVICE_LOST: return "device lost (VK_ERROR_DEVICE_LOST)";
        case VK_ERROR_LAYER_NOT_PRESENT: return "layer not present (VK_ERROR_LAYER_NOT_PRESENT)";
        case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
        case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
        case VK_ERROR_INCOMPATIBLE_DRIVER: return "no compatible Vulkan driver (VK_ERROR_INCOMPATIBLE_DRIVER)";
        case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
        default: return "VkResult error";
    }
}

void check(VkResult result, const char* what) {
    if (result == VK_ERROR_OUT_OF_HOST_MEMORY || result == VK_ERROR_OUT_OF_DEVICE_MEMORY)
        throw OutOfMemory(std::string("Vulkan ") + what + ": " + result_name(result) + " (" +
                          std::to_string(int(result)) + ")");
    if (result != VK_SUCCESS)
        throw Error(ErrorKind::Device, std::string("Vulkan ") + what + ": " + result_name(result) + " (" +
                                           std::to_string(int(result)) + ")");
}

}  // namespace vkfuse::vk

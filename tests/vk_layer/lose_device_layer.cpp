// VK_LAYER_VKFUSE_lose_device: a Vulkan layer for tests that loses the device.
// vkWaitForFences waits as usual, then answers VK_ERROR_DEVICE_LOST once
// VKFUSE_TEST_LOSE_DEVICE_AFTER (default 0) waits have succeeded, the way a
// GPU reset or a driver crash mid-run surfaces. lavapipe never loses its
// device; with this layer the tests see what a plan and the CLI make of it.
// Enabled by VK_ADD_LAYER_PATH=<directory of its manifest> and
// VK_INSTANCE_LAYERS=VK_LAYER_VKFUSE_lose_device. One instance and one device
// at a time, which is all the tests create while it is on.
#include <vulkan/vk_layer.h>

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace {

PFN_vkGetInstanceProcAddr next_instance_proc = nullptr;
PFN_vkGetDeviceProcAddr next_device_proc = nullptr;
PFN_vkWaitForFences next_wait_for_fences = nullptr;
std::atomic<long> waits_before_loss{0};

// The loader's link to the next layer or driver, found in pNext.
template <class Info>
Info* link_info(const void* next, VkStructureType type) {
    for (auto* s = static_cast<const VkBaseInStructure*>(next); s; s = s->pNext)
        if (s->sType == type && reinterpret_cast<const Info*>(s)->function == VK_LAYER_LINK_INFO)
            return const_cast<Info*>(reinterpret_cast<const Info*>(s));
    return nullptr;
}

VKAPI_ATTR VkResult VKAPI_CALL create_instance(const VkInstanceCreateInfo* info, const VkAllocationCallbacks* alloc,
                                               VkInstance* instance) {
    auto* link = link_info<VkLayerInstanceCreateInfo>(info->pNext, VK_STRUCTURE_TYPE_LOADER_INSTANCE_CREATE_INFO);
    if (!link) return VK_ERROR_INITIALIZATION_FAILED;
    next_instance_proc = link->u.pLayerInfo->pfnNextGetInstanceProcAddr;
    link->u.pLayerInfo = link->u.pLayerInfo->pNext;  // the next layer finds its own link
    auto create = reinterpret_cast<PFN_vkCreateInstance>(next_instance_proc(nullptr, "vkCreateInstance"));
    const char* after = std::getenv("VKFUSE_TEST_LOSE_DEVICE_AFTER");
    waits_before_loss = after ? std::atol(after) : 0;
    return create(info, alloc, instance);
}

VKAPI_ATTR VkResult VKAPI_CALL create_device(VkPhysicalDevice physical, const VkDeviceCreateInfo* info,
                                             const VkAllocationCallbacks* alloc, VkDevice* device) {
    auto* link = link_info<VkLayerDeviceCreateInfo>(info->pNext, VK_STRUCTURE_TYPE_LOADER_DEVICE_CREATE_INFO);
    if (!link) return VK_ERROR_INITIALIZATION_FAILED;
    PFN_vkGetInstanceProcAddr instance_proc = link->u.pLayerInfo->pfnNextGetInstanceProcAddr;
    next_device_proc = link->u.pLayerInfo->pfnNextGetDeviceProcAddr;
    link->u.pLayerInfo = link->u.pLayerInfo->pNext;
    auto create = reinterpret_cast<PFN_vkCreateDevice>(instance_proc(nullptr, "vkCreateDevice"));
    const VkResult result = create(physical, info, alloc, device);
    if (result == VK_SUCCESS)
        next_wait_for_fences = reinterpret_cast<PFN_vkWaitForFences>(next_device_proc(*device, "vkWaitForFences"));
    return result;
}

VKAPI_ATTR VkResult VKAPI_CALL wait_for_fences(VkDevice device, uint32_t count, const VkFence* fences, VkBool32 all,
                                               uint64_t timeout) {
    const VkResult result = next_wait_for_fences(device, count, fences, all, timeout);
    if (result != VK_SUCCESS) return result;
    return waits_before_loss.fetch_sub(1) > 0 ? VK_SUCCESS : VK_ERROR_DEVICE_LOST;
}

}  // namespace

extern "C" {

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkfuse_lose_device_GetDeviceProcAddr(VkDevice device, const char* name) {
    if (std::strcmp(name, "vkWaitForFences") == 0) return reinterpret_cast<PFN_vkVoidFunction>(&wait_for_fences);
    if (std::strcmp(name, "vkGetDeviceProcAddr") == 0)
        return reinterpret_cast<PFN_vkVoidFunction>(&vkfuse_lose_device_GetDeviceProcAddr);
    return next_device_proc ? next_device_proc(device, name) : nullptr;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkfuse_lose_device_GetInstanceProcAddr(VkInstance instance, const char* name) {
    if (std::strcmp(name, "vkCreateInstance") == 0) return reinterpret_cast<PFN_vkVoidFunction>(&create_instance);
    if (std::strcmp(name, "vkCreateDevice") == 0) return reinterpret_cast<PFN_vkVoidFunction>(&create_device);
    if (std::strcmp(name, "vkGetInstanceProcAddr") == 0)
        return reinterpret_cast<PFN_vkVoidFunction>(&vkfuse_lose_device_GetInstanceProcAddr);
    if (std::strcmp(name, "vkGetDeviceProcAddr") == 0 || std::strcmp(name, "vkWaitForFences") == 0)
        return vkfuse_lose_device_GetDeviceProcAddr(VK_NULL_HANDLE, name);
    return next_instance_proc ? next_instance_proc(instance, name) : nullptr;
}

}  // extern "C"

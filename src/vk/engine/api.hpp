// The Vulkan entry points vkfuse uses, loaded at run time from libvulkan.so.1.
// Loading instead of linking means a machine without a Vulkan loader still runs
// the CPU path and gets one clear message instead of a failed program start.
// Each Context owns its own table: no global state.
#pragma once
#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

#include <memory>

namespace vkfuse::vk {

#define VKFUSE_GLOBAL_FUNCS(X)                \
    X(vkCreateInstance)                       \
    X(vkEnumerateInstanceVersion)             \
    X(vkEnumerateInstanceLayerProperties)     \
    X(vkEnumerateInstanceExtensionProperties)

#define VKFUSE_INSTANCE_FUNCS(X)                  \
    X(vkDestroyInstance)                          \
    X(vkEnumeratePhysicalDevices)                 \
    X(vkGetPhysicalDeviceProperties)              \
    X(vkGetPhysicalDeviceProperties2)             \
    X(vkGetPhysicalDeviceFeatures2)               \
    X(vkGetPhysicalDeviceQueueFamilyProperties)   \
    X(vkGetPhysicalDeviceMemoryProperties)        \
    X(vkGetPhysicalDeviceMemoryProperties2)       \
    X(vkGetPhysicalDeviceExternalBufferProperties) \
    X(vkCreateDevice)                             \
    X(vkEnumerateDeviceExtensionProperties)       \
    X(vkGetDeviceProcAddr)

#define VKFUSE_DEBUG_FUNCS(X)            \
    X(vkCreateDebugUtilsMessengerEXT)    \
    X(vkDestroyDebugUtilsMessengerEXT)

#define VKFUSE_DEVICE_FUNCS(X)            \
    X(vkDestroyDevice)                    \
    X(vkGetDeviceQueue)                   \
    X(vkCreateBuffer)                     \
    X(vkDestroyBuffer)                    \
    X(vkGetBufferMemoryRequirements)      \
    X(vkAllocateMemory)                   \
    X(vkFreeMemory)                       \
    X(vkBindBufferMemory)                 \
    X(vkMapMemory)                        \
    X(vkUnmapMemory)                      \
    X(vkInvalidateMappedMemoryRanges)     \
    X(vkGetBufferDeviceAddress)           \
    X(vkCreateShaderModule)               \
    X(vkDestroyShaderModule)              \
    X(vkCreatePipelineLayout)             \
    X(vkDestroyPipelineLayout)            \
    X(vkCreateComputePipelines)           \
    X(vkCreatePipelineCache)              \
    X(vkDestroyPipelineCache)             \
    X(vkGetPipelineCacheData)             \
    X(vkDestroyPipeline)                  \
    X(vkCreateCommandPool)                \
    X(vkDestroyCommandPool)               \
    X(vkAllocateCommandBuffers)           \
    X(vkFreeCommandBuffers)               \
    X(vkBeginCommandBuffer)               \
    X(vkEndCommandBuffer)                 \
    X(vkResetCommandBuffer)               \
    X(vkCmdBindPipeline)                  \
    X(vkCmdPushConstants)                 \
    X(vkCmdDispatch)                      \
    X(vkCmdDispatchIndirect)              \
    X(vkCmdPipelineBarrier)               \
    X(vkCmdCopyBuffer)                    \
    X(vkCmdFillBuffer)                    \
    X(vkCmdResetQueryPool)                \
    X(vkCmdWriteTimestamp)                \
    X(vkCreateQueryPool)                  \
    X(vkDestroyQueryPool)                 \
    X(vkGetQueryPoolResults)              \
    X(vkCreateFence)                      \
    X(vkDestroyFence)                     \
    X(vkResetFences)                      \
    X(vkWaitForFences)                    \
    X(vkQueueSubmit)                      \
    X(vkDeviceWaitIdle)                   \
    X(vkCreateDescriptorSetLayout)        \
    X(vkDestroyDescriptorSetLayout)       \
    X(vkCreateDescriptorPool)             \
    X(vkDestroyDescriptorPool)            \
    X(vkAllocateDescriptorSets)           \
    X(vkUpdateDescriptorSets)             \
    X(vkCmdBindDescriptorSets)            \
    X(vkCmdExecuteCommands)               \
    X(vkCreateSemaphore)                  \
    X(vkDestroySemaphore)                 \
    X(vkWaitSemaphores)

// Extension entry points, loaded where the device has them (null otherwise).
#define VKFUSE_DEVICE_OPTIONAL_FUNCS(X) \
    X(vkGetMemoryFdKHR)                 \
    X(vkGetMemoryHostPointerPropertiesEXT)

#define VKFUSE_DECLARE(name) PFN_##name name = nullptr;

// One loaded libvulkan plus the function pointers of one instance and device.
struct Api {
    VKFUSE_GLOBAL_FUNCS(VKFUSE_DECLARE)
    VKFUSE_INSTANCE_FUNCS(VKFUSE_DECLARE)
    VKFUSE_DEBUG_FUNCS(VKFUSE_DECLARE)
    VKFUSE_DEVICE_FUNCS(VKFUSE_DECLARE)
    VKFUSE_DEVICE_OPTIONAL_FUNCS(VKFUSE_DECLARE)
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;

    // dlopen()s the loader (libvulkan.so.1, or the path in VKFUSE_VULKAN_LIBRARY);
    // throws Error(Device) "Vulkan loader libvulkan.so.1 not found".
    static std::unique_ptr<Api> load();
    // The entry points behind a caller's vkGetInstanceProcAddr (null: load()'s).
    static std::unique_ptr<Api> adopt(PFN_vkGetInstanceProcAddr get_instance_proc_addr);
    void load_instance(VkInstance instance);  // instance + debug-utils entry points
    void load_device(VkDevice device);        // device entry points (throws if one is missing)

    Api() = default;
    ~Api();
    Api(const Api&) = delete;
    Api& operator=(const Api&) = delete;

private:
    void* library_ = nullptr;  // null for adopt()ed entry points
    void load_global();
};

// Throws Error(Device) "<what>: <VkResult name>" unless result is VK_SUCCESS.
void check(VkResult result, const char* what);
const char* result_name(VkResult result);

}  // namespace vkfuse::vk

// The caller's side of embedding vkfuse: a Vulkan instance, device, queue
// and buffers a perception stack would already own. vkfuse is handed these
// (vkfuse::make_context) and never destroys them. Header-only, for
// examples/caller_command_buffer and the tests that embed plans the same way.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <vkfuse/vk/interop.hpp>

namespace caller {

inline void check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed: VkResult " + std::to_string(int(r)));
}

// A host-visible buffer every vkfuse use accepts (storage, device address,
// transfers), with its memory mapped.
struct HostBuffer {
    VkDevice device = VK_NULL_HANDLE;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;

    HostBuffer() = default;
    HostBuffer(const HostBuffer&) = delete;
    HostBuffer& operator=(const HostBuffer&) = delete;
    HostBuffer(HostBuffer&& o) noexcept { *this = std::move(o); }
    HostBuffer& operator=(HostBuffer&& o) noexcept {
        std::swap(device, o.device);
        std::swap(buffer, o.buffer);
        std::swap(memory, o.memory);
        std::swap(size, o.size);
        std::swap(mapped, o.mapped);
        return *this;
    }
    ~HostBuffer() {
        if (buffer) vkDestroyBuffer(device, buffer, nullptr);
        if (memory) vkFreeMemory(device, memory, nullptr);
    }
    vkfuse::BufferRange range(VkDeviceSize offset = 0) const { return {buffer, offset, size - offset}; }
};

// Counts validation messages; prints each.
inline VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                  VkDebugUtilsMessageTypeFlagsEXT types,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (!(types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT)) return VK_FALSE;
    ++*static_cast<std::uint64_t*>(user);
    std::fprintf(stderr, "validation: %s\n", data->pMessage);
    return VK_FALSE;
}

// Whether the loader knows an instance layer of this name: a GPU machine
// often has no validation layers installed, and asking for one then fails
// vkCreateInstance.
inline bool layer_installed(const char* name) {
    std::uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const VkLayerProperties& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

class Device {
public:
    // validation: VK_LAYER_KHRONOS_validation on where it is installed, its
    // messages counted (validating() says whether it is on).
    explicit Device(bool validation) {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "caller";
        app.apiVersion = VK_API_VERSION_1_2;
        const char* layer = "VK_LAYER_KHRONOS_validation";
        const char* debug = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
        dbg.pfnUserCallback = on_message;
        dbg.pUserData = &messages_;
        VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ici.pApplicationInfo = &app;
        validation = validation && layer_installed(layer);
        validating_ = validation;
        if (validation) {
            ici.pNext = &dbg;
            ici.enabledLayerCount = 1;
            ici.ppEnabledLayerNames = &layer;
            ici.enabledExtensionCount = 1;
            ici.ppEnabledExtensionNames = &debug;
        }
        check(vkCreateInstance(&ici, nullptr, &instance_), "vkCreateInstance");
        if (validation) {
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
            check(create(instance_, &dbg, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
        }
        std::uint32_t n = 0;
        vkEnumeratePhysicalDevices(instance_, &n, nullptr);
        std::vector<VkPhysicalDevice> devices(n);
        vkEnumeratePhysicalDevices(instance_, &n, devices.data());
        if (devices.empty()) throw std::runtime_error("no Vulkan device");
        physical_ = devices.front();
        std::uint32_t f = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical_, &f, nullptr);
        std::vector<VkQueueFamilyProperties> families(f);
        vkGetPhysicalDeviceQueueFamilyProperties(physical_, &f, families.data());
        while (family_ < f && !(families[family_].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family_;
        if (family_ == f) throw std::runtime_error("no compute queue");
        create_device();
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pci.queueFamilyIndex = family_;
        check(vkCreateCommandPool(device_, &pci, nullptr, &pool_), "vkCreateCommandPool");
    }
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;
    ~Device() {
        vkDeviceWaitIdle(device_);
        vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
        if (messenger_) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
            destroy(instance_, messenger_, nullptr);
        }
        vkDestroyInstance(instance_, nullptr);
    }

    // What vkfuse::make_context needs to know of this device.
    vkfuse::CallerDevice describe() const {
        vkfuse::CallerDevice d;
        d.instance = instance_;
        d.physical_device = physical_;
        d.device = device_;
        d.queue_family = family_;
        d.get_instance_proc_addr = vkGetInstanceProcAddr;
        d.shader_float64 = float64_;
        d.external_memory_fd = memory_fd_;
        d.external_memory_host = memory_host_;
        return d;
    }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    std::uint64_t validation_messages() const { return messages_; }
    bool validating() const { return validating_; }

    HostBuffer buffer(VkDeviceSize bytes) const {
        HostBuffer b;
        b.device = device_;
        b.size = bytes;
        VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        bci.size = bytes;
        bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                    VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        check(vkCreateBuffer(device_, &bci, nullptr, &b.buffer), "vkCreateBuffer");
        VkMemoryRequirements req{};
        vkGetBufferMemoryRequirements(device_, b.buffer, &req);
        VkPhysicalDeviceMemoryProperties mem{};
        vkGetPhysicalDeviceMemoryProperties(physical_, &mem);
        const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        std::uint32_t type = 0;
        while (type < mem.memoryTypeCount &&
               (!(req.memoryTypeBits & (1u << type)) || (mem.memoryTypes[type].propertyFlags & host) != host))
            ++type;
        if (type == mem.memoryTypeCount) throw std::runtime_error("no host-visible memory");
        VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
        flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        mai.pNext = &flags;
        mai.allocationSize = req.size;
        mai.memoryTypeIndex = type;
        check(vkAllocateMemory(device_, &mai, nullptr, &b.memory), "vkAllocateMemory");
        check(vkBindBufferMemory(device_, b.buffer, b.memory, 0), "vkBindBufferMemory");
        check(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
        return b;
    }

    VkCommandBuffer begin() const {
        VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cai.commandPool = pool_;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        check(vkAllocateCommandBuffers(device_, &cai, &cmd), "vkAllocateCommandBuffers");
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
        return cmd;
    }
    // Ends cmd, submits it after `wait` reaches wait_value (a timeline
    // semaphore; none when null), waits on the host, and frees it.
    void submit_and_wait(VkCommandBuffer cmd, VkSemaphore wait = VK_NULL_HANDLE, std::uint64_t wait_value = 0) const {
        check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
        VkTimelineSemaphoreSubmitInfo tsi{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
        tsi.waitSemaphoreValueCount = wait ? 1 : 0;
        tsi.pWaitSemaphoreValues = &wait_value;
        const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.pNext = &tsi;
        si.waitSemaphoreCount = wait ? 1 : 0;
        si.pWaitSemaphores = &wait;
        si.pWaitDstStageMask = &stage;
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd;
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkFence fence = VK_NULL_HANDLE;
        check(vkCreateFence(device_, &fci, nullptr, &fence), "vkCreateFence");
        check(vkQueueSubmit(queue_, 1, &si, fence), "vkQueueSubmit");
        check(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        vkDestroyFence(device_, fence, nullptr);
        vkFreeCommandBuffers(device_, pool_, 1, &cmd);
    }

private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::uint32_t family_ = 0;
    bool float64_ = false, memory_fd_ = false, memory_host_ = false;
    std::uint64_t messages_ = 0;
    bool validating_ = false;

    // Vulkan 1.2's bufferDeviceAddress and timelineSemaphore (vkfuse needs
    // both), doubles where the device has them, and the external-memory
    // extensions where it offers them.
    void create_device() {
        VkPhysicalDeviceVulkan12Features has12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        VkPhysicalDeviceFeatures2 has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        has.pNext = &has12;
        vkGetPhysicalDeviceFeatures2(physical_, &has);
        if (!has12.bufferDeviceAddress || !has12.timelineSemaphore)
            throw std::runtime_error("the device lacks bufferDeviceAddress or timelineSemaphore");
        float64_ = has.features.shaderFloat64;
        std::uint32_t n = 0;
        vkEnumerateDeviceExtensionProperties(physical_, nullptr, &n, nullptr);
        std::vector<VkExtensionProperties> offered(n);
        vkEnumerateDeviceExtensionProperties(physical_, nullptr, &n, offered.data());
        std::vector<const char*> extensions;
        for (const auto& x : offered) {
            if (std::strcmp(x.extensionName, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME) == 0) {
                memory_fd_ = true;
                extensions.push_back(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
            }
            if (std::strcmp(x.extensionName, VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME) == 0) {
                memory_host_ = true;
                extensions.push_back(VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME);
            }
        }
        VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        f12.bufferDeviceAddress = VK_TRUE;
        f12.timelineSemaphore = VK_TRUE;
        VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        f.pNext = &f12;
        f.features.shaderFloat64 = float64_;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qci.queueFamilyIndex = family_;
        qci.queueCount = 1;
        qci.pQueuePriorities = &priority;
        VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        dci.pNext = &f;
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        dci.enabledExtensionCount = std::uint32_t(extensions.size());
        dci.ppEnabledExtensionNames = extensions.data();
        check(vkCreateDevice(physical_, &dci, nullptr, &device_), "vkCreateDevice");
        vkGetDeviceQueue(device_, family_, 0, &queue_);
    }
};

}  // namespace caller

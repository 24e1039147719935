#include "vk/engine/memory_types.hpp"

#include <algorithm>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

constexpr VkMemoryPropertyFlags kDeviceLocal = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
constexpr VkMemoryPropertyFlags kVisible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
constexpr VkMemoryPropertyFlags kCoherent = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
constexpr VkMemoryPropertyFlags kCached = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;

// The heaps of the discrete profile (vk/engine/device_profile.cpp): the GPU's own
// memory, system memory, and the PCI BAR window of a host without resizable BAR.
constexpr VkDeviceSize kVideoMemory = VkDeviceSize(8) << 30;
constexpr VkDeviceSize kBarWindow = VkDeviceSize(256) << 20;

}  // namespace

void MemoryTypes::use_device(const VkPhysicalDeviceMemoryProperties& real) {
    visible_ = real;
    for (std::uint32_t i = 0; i < real.memoryTypeCount; ++i) real_type_[i] = i;
    shadowed_.fill(false);
    simulated_ = false;
}

void MemoryTypes::simulate_discrete(const VkPhysicalDeviceMemoryProperties& real) {
    int backing = -1;
    for (std::uint32_t i = 0; i < real.memoryTypeCount && backing < 0; ++i)
        if ((real.memoryTypes[i].propertyFlags & (kVisible | kCoherent)) == (kVisible | kCoherent)) backing = int(i);
    if (backing < 0) throw Error(ErrorKind::Device, "device profile discrete-no-rebar: no host-visible coherent memory to back it");
    const VkDeviceSize system = real.memoryHeaps[real.memoryTypes[backing].heapIndex].size;
    visible_ = {};
    visible_.memoryHeapCount = 3;
    visible_.memoryHeaps[0] = {kVideoMemory, VK_MEMORY_HEAP_DEVICE_LOCAL_BIT};
    visible_.memoryHeaps[1] = {system, 0};
    visible_.memoryHeaps[2] = {kBarWindow, VK_MEMORY_HEAP_DEVICE_LOCAL_BIT};
    visible_.memoryTypeCount = 4;
    visible_.memoryTypes[0] = {kDeviceLocal, 0};
    visible_.memoryTypes[1] = {kVisible | kCoherent, 1};
    visible_.memoryTypes[2] = {kVisible | kCached, 1};  // not coherent: shadowed
    visible_.memoryTypes[3] = {kDeviceLocal | kVisible | kCoherent, 2};
    real_type_.fill(std::uint32_t(backing));
    shadowed_.fill(false);
    shadowed_[2] = true;
    simulated_ = true;
}

std::uint32_t MemoryTypes::visible_bits(std::uint32_t real_bits) const {
    std::uint32_t bits = 0;
    for (std::uint32_t i = 0; i < visible_.memoryTypeCount; ++i)
        if (real_bits >> real_type_[i] & 1u) bits |= 1u << i;
    return bits;
}

bool MemoryTypes::shadowed(std::uint32_t type) const { return shadowed_[type]; }

bool MemoryTypes::has_device_local() const {
    for (std::uint32_t i = 0; i < visible_.memoryTypeCount; ++i)
        if (visible_.memoryTypes[i].propertyFlags & kDeviceLocal) return true;
    return false;
}

VkResult MemoryTypes::allocate(const Api& api, VkDevice device, VkMemoryAllocateInfo info, VkDeviceMemory* memory) {
    const std::uint32_t type = info.memoryTypeIndex;
    if (type >= visible_.memoryTypeCount) return VK_ERROR_OUT_OF_DEVICE_MEMORY;
    const std::uint32_t heap = visible_.memoryTypes[type].heapIndex;
    // Counted first: two threads cannot both take the last of a simulated heap.
    const VkDeviceSize before = used_[heap].fetch_add(info.allocationSize);
    if (simulated_ && before + info.allocationSize > visible_.memoryHeaps[heap].size) {
        used_[heap].fetch_sub(info.allocationSize);
        return VK_ERROR_OUT_OF_DEVICE_MEMORY;
    }
    info.memoryTypeIndex = real_type_[type];
    const VkResult r = api.vkAllocateMemory(device, &info, nullptr, memory);
    if (r != VK_SUCCESS) used_[heap].fetch_sub(info.allocationSize);
    return r;
}

void MemoryTypes::free(const Api& api, VkDevice device, VkDeviceMemory memory, std::uint32_t type, VkDeviceSize bytes) {
    if (!memory) return;
    api.vkFreeMemory(device, memory, nullptr);
    used_[visible_.memoryTypes[type].heapIndex].fetch_sub(bytes);
}

bool MemoryTypes::host_visible_heap(std::uint32_t heap) const {
    for (std::uint32_t i = 0; i < visible_.memoryTypeCount; ++i)
        if (visible_.memoryTypes[i].heapIndex == heap && (visible_.memoryTypes[i].propertyFlags & kVisible)) return true;
    return false;
}

std::string MemoryTypes::describe_heap(std::uint32_t heap) const {
    const bool visible = host_visible_heap(heap);
    const bool local = visible_.memoryHeaps[heap].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT;
    return std::string(local ? "device-local" : "system") + (local && visible ? " host-visible" : "") + " heap " +
           std::to_string(heap) + " (" + std::to_string(visible_.memoryHeaps[heap].size >> 20) + " MiB)";
}

std::vector<std::uint32_t> MemoryTypes::ranked(std::uint32_t type_bits,
                                             std::initializer_list<VkMemoryPropertyFlags> preferences) const {
    std::vector<std::uint32_t> types;
    for (VkMemoryPropertyFlags wanted : preferences)
        for (std::uint32_t i = 0; i < visible_.memoryTypeCount; ++i)
            if ((type_bits >> i & 1u) && (visible_.memoryTypes[i].propertyFlags & wanted) == wanted &&
                std::find(types.begin(), types.end(), i) == types.end())
                types.push_back(i);
    return types;
}

}  // namespace vkfuse::vk

// The memory types and heaps the library sees, and every allocation it makes
// from them. Normally the device's own; under a discrete-memory profile
// (vk/engine/device_profile.hpp) the heaps of a discrete GPU without resizable BAR,
// backed by the device's memory: each heap's size is enforced here as a real
// device would (VK_ERROR_OUT_OF_DEVICE_MEMORY once full), and a simulated
// non-coherent type over coherent memory is shadowed (vk/engine/buffer.cpp), so that
// a read-back missing its invalidation reads stale bytes here too.
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "vk/engine/api.hpp"

namespace vkfuse::vk {

class MemoryTypes {
public:
    // The device's own types and heaps.
    void use_device(const VkPhysicalDeviceMemoryProperties& real);
    // A discrete GPU's: device-local, system coherent, system cached (not
    // coherent) and a 256 MiB device-local host-visible heap, all backed by
    // the real type with every host flag. Throws Error(Device) where the real
    // device has no such type.
    void simulate_discrete(const VkPhysicalDeviceMemoryProperties& real);

    const VkPhysicalDeviceMemoryProperties& properties() const { return visible_; }
    bool simulated() const { return simulated_; }
    bool has_device_local() const;  // some type is DEVICE_LOCAL
    // Visible types whose real type is among real_bits (a buffer's memoryTypeBits).
    std::uint32_t visible_bits(std::uint32_t real_bits) const;
    // The visible types among type_bits with every flag of the first
    // preference, then those with the next's, and so on: best first, each
    // once; empty where none has even the last's. Every choice of a memory
    // type is made here (vk/engine/buffer.cpp, vk/engine/device_memory.cpp).
    std::vector<std::uint32_t> ranked(std::uint32_t type_bits,
                                      std::initializer_list<VkMemoryPropertyFlags> preferences) const;
    // Whether memory of visible type `type` is shadowed: the host works on a
    // copy that only flush/invalidate exchange with the memory.
    bool shadowed(std::uint32_t type) const;

    // vkAllocateMemory of info (its memoryTypeIndex a visible type), counted
    // against the type's heap; a simulated heap that is full answers
    // VK_ERROR_OUT_OF_DEVICE_MEMORY without asking the driver.
    VkResult allocate(const Api& api, VkDevice device, VkMemoryAllocateInfo info, VkDeviceMemory* memory);
    void free(const Api& api, VkDevice device, VkDeviceMemory memory, std::uint32_t type, VkDeviceSize bytes);

    VkDeviceSize heap_used(std::uint32_t heap) const { return used_[heap].load(); }
    std::uint32_t heap_of(std::uint32_t type) const { return visible_.memoryTypes[type].heapIndex; }
    bool host_visible_heap(std::uint32_t heap) const;  // some type in it is HOST_VISIBLE
    // "device-local host-visible heap 2 (256 MiB)"
    std::string describe_heap(std::uint32_t heap) const;

private:
    VkPhysicalDeviceMemoryProperties visible_{};
    std::array<std::uint32_t, VK_MAX_MEMORY_TYPES> real_type_{};
    std::array<bool, VK_MAX_MEMORY_TYPES> shadowed_{};
    std::array<std::atomic<VkDeviceSize>, VK_MAX_MEMORY_HEAPS> used_{};
    bool simulated_ = false;
};

}  // namespace vkfuse::vk

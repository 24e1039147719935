// Simulated device profiles: lavapipe (or any device) seen through the limits
// and memory of a GPU class it is not, so that the library's adaptations to
// that class run and are tested on every machine. ContextOptions::device_profile
// or VKFUSE_DEVICE_PROFILE picks one; a profile only ever lowers what the real
// device offers, so everything vkfuse does under it is valid on the real one.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "vk/engine/api.hpp"

namespace vkfuse::vk {

struct DeviceProfile {
    std::string_view name;
    std::string_view summary;  // one line: the GPU class and where its figures come from
    // Limits it imposes; 0 keeps the device's own.
    std::uint32_t storage_buffers_per_stage = 0;  // maxPerStageDescriptorStorageBuffers
    std::uint32_t storage_buffer_range = 0;       // maxStorageBufferRange
    std::uint32_t storage_offset_alignment = 0;   // minStorageBufferOffsetAlignment
    std::uint32_t shared_memory_bytes = 0;        // maxComputeSharedMemorySize
    std::uint32_t workgroup_invocations = 0;      // maxComputeWorkGroupInvocations
    bool device_addresses = true;                 // bufferDeviceAddress
    // The heaps and memory types of a discrete GPU without resizable BAR
    // (vk/engine/memory_types.hpp) instead of the device's own.
    bool discrete_memory = false;
    // Treat the device as one whose kernels may flush float32 subnormals
    // (DeviceInfo::float32_subnormals false), as GPUs without
    // shaderDenormPreserveFloat32 do.
    bool flushes_subnormals = false;
};

// Every profile, in the order `vkfuse info` lists them.
std::span<const DeviceProfile> device_profiles();

// The profile called name. Throws Error(InvalidArgument) "<subject>=<name>:
// no such device profile (a, b, c)" for any other.
const DeviceProfile& find_device_profile(std::string_view name, std::string_view subject);

// The device's limits as the profile sees them (each the lower of the two).
void apply_limits(const DeviceProfile& profile, VkPhysicalDeviceLimits& limits);

}  // namespace vkfuse::vk

#include "vk/engine/device_profile.hpp"

#include <algorithm>
#include <array>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

// The figures, and where they come from:
//
// discrete-no-rebar: a desktop GPU (NVIDIA, AMD) on a host without resizable
//   BAR, whose kernels may flush float32 subnormals (NVIDIA's offer no
//   shaderDenormPreserveFloat32). Its host-visible device-local memory is the PCI BAR window, a heap of
//   256 MiB beside the GPU's own memory and system memory (the layout AMD's
//   "Vulkan Memory Types on PC and how to use them", GPUOpen 2018, describes
//   for every desktop vendor). Read-back is cached and not coherent, as on
//   Arm Mali and Qualcomm Adreno (HOST_VISIBLE | HOST_CACHED without
//   HOST_COHERENT): the one class whose reads need vkInvalidateMappedMemoryRanges.
//
// phone: a phone-class GPU. Storage buffers per stage, binding range, offset
//   alignment and shared memory are Khronos's VP_ANDROID_baseline_2021
//   profile (KhronosGroup/Vulkan-Profiles, profiles/VP_ANDROID_baseline_2021.json:
//   maxPerStageDescriptorStorageBuffers 4, maxStorageBufferRange 134217728,
//   minStorageBufferOffsetAlignment 256, maxComputeSharedMemorySize 16384),
//   which are also the Vulkan specification's required minima. That baseline
//   guarantees 128 invocations per workgroup; vkfuse's kernels use 256, which
//   current Mali and Adreno GPUs offer, so the profile has 256 and a device
//   with fewer is refused naming the kernel (Context checks every kernel).
//   Its kernels may flush float32 subnormals, as mobile GPUs' commonly do.
//
// no-device-address: a Vulkan 1.2 device without bufferDeviceAddress (an
//   optional feature in 1.2; older Mali and Adreno drivers and some embedded
//   GPUs lack it).
constexpr std::array kProfiles{
    DeviceProfile{"discrete-no-rebar",
                  "discrete GPU without resizable BAR: a 256 MiB host-visible device-local heap, non-coherent cached "
                  "read-back",
                  0, 0, 0, 0, 0, true, true, true},
    DeviceProfile{"phone",
                  "phone-class GPU (VP_ANDROID_baseline_2021 limits): 4 storage buffers per stage, 128 MiB per "
                  "binding, 256-byte offsets, 16 KiB shared memory, 256 invocations",
                  4, 128u << 20, 256, 16u << 10, 256, true, false, true},
    DeviceProfile{"no-device-address", "a Vulkan 1.2 device without bufferDeviceAddress", 0, 0, 0, 0, 0, false, false},
};

void lower(std::uint32_t& limit, std::uint32_t to) {
    if (to != 0) limit = std::min(limit, to);
}

}  // namespace

std::span<const DeviceProfile> device_profiles() { return kProfiles; }

const DeviceProfile& find_device_profile(std::string_view name, std::string_view subject) {
    std::string names;
    for (const DeviceProfile& p : kProfiles) {
        if (p.name == name) return p;
        names += (names.empty() ? "" : ", ") + std::string(p.name);
    }
    throw Error(ErrorKind::InvalidArgument, std::string(subject) + "=" + std::string(name.substr(0, 40)) +
                                                ": no such device profile (" + names + ")");
}

void apply_limits(const DeviceProfile& profile, VkPhysicalDeviceLimits& limits) {
    lower(limits.maxPerStageDescriptorStorageBuffers, profile.storage_buffers_per_stage);
    lower(limits.maxDescriptorSetStorageBuffers, profile.storage_buffers_per_stage * 6);  // the baseline's 24
    lower(limits.maxStorageBufferRange, profile.storage_buffer_range);
    lower(limits.maxComputeSharedMemorySize, profile.shared_memory_bytes);
    lower(limits.maxComputeWorkGroupInvocations, profile.workgroup_invocations);
    if (profile.storage_offset_alignment != 0)  // an alignment is a lower limit: the larger holds on both
        limits.minStorageBufferOffsetAlignment =
            std::max<VkDeviceSize>(limits.minStorageBufferOffsetAlignment, profile.storage_offset_alignment);
}

}  // namespace vkfuse::vk

// vkfuse/vk/interop.hpp - vkfuse inside a caller's own Vulkan work.
//
// Ordinary use needs none of this (vk/context.hpp, vk/plan.hpp). This header
// is for perception stacks that already hold a Vulkan device:
//   - a Context on the caller's VkDevice and queue (the caller keeps them);
//   - a Plan that reads its frames from, and writes its fused image to,
//     buffers of that device, with no host copy;
//   - the plan's cycle appended to the caller's command buffer, or submitted
//     without waiting and signalling a timeline semaphore, so capture, fusion
//     and the caller's own GPU work overlap;
//   - memory shared with another device or process (an opaque fd,
//     VK_KHR_external_memory_fd) or with the host (a pointer,
//     VK_EXT_external_memory_host): frames arrive with no staging copy.
// Only Vulkan's types are used here (vulkan_core.h); vkfuse loads its entry
// points itself, from the caller's vkGetInstanceProcAddr where given.
#pragma once
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <memory>
#include <span>

#include "vkfuse/core/image.hpp"
#include "vkfuse/vk/context.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse {

// The caller's device, as the caller created it. Requirements: an instance of
// API 1.2 or later, a device with the Vulkan 1.2 features bufferDeviceAddress
// and timelineSemaphore enabled, and a queue family with compute. The flags
// below say what else the caller enabled, which vkfuse then uses; vkfuse
// cannot query what a device was created with, so a flag set for a feature
// not enabled is the caller's error (the validation layer reports it).
struct CallerDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t queue_family = 0;  // must support compute
    std::uint32_t queue_index = 0;
    // Where vkfuse finds the entry points; null: the loader's (libvulkan.so.1).
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    bool shader_float64 = false;       // shaderFloat64: FilterArithmetic::Float64 available
    bool fp16_storage = false;         // storageBuffer16BitAccess: Precision::Fp16Storage
    bool external_memory_fd = false;   // VK_KHR_external_memory_fd: DeviceMemory's fd import and export
    bool external_memory_host = false; // VK_EXT_external_memory_host: DeviceMemory::import_host
    // bufferDeviceAddress enabled (kernels beyond a binding's range, or with
    // more buffers than a stage may bind, reach them by address). false:
    // vkfuse binds every buffer and refuses plans that would need addresses.
    bool buffer_device_address = true;
};

// A Context on the caller's device. vkfuse creates only its own objects
// (pipelines, buffers, command pools, semaphores) and destroys them with the
// Context; the device, instance and queue stay the caller's, and must outlive
// the Context. Vulkan requires the queue's submissions to be externally
// synchronised: vkfuse submits to it only inside Plan::run and
// vkfuse::submit, so the caller must not submit to the same queue from another
// thread at the same time (or record plans into its own command buffers and
// submit those itself). options.device_index and options.validation do not
// apply (the caller's instance has its own layers), nor does a device profile.
// Queue families: vkfuse submits only to the caller's queue, in family
// `queue_family`, and transfers no ownership; a buffer of the caller's
// (BufferRange) that another queue family also uses must be created
// VK_SHARING_MODE_CONCURRENT, or released to and acquired from that family
// by the caller around vkfuse's work. Throws Error(Device) for a device that
// does not meet the requirements.
Context make_context(const CallerDevice& device, const ContextOptions& options = {});

// A byte range of a buffer on the context's device. The buffer must have been
// created with VK_BUFFER_USAGE_STORAGE_BUFFER_BIT and, where the context uses
// device addresses, VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT (its memory
// allocated with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT), and offset must be a multiple of
// 16 and of the device's minStorageBufferOffsetAlignment.
struct BufferRange {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
};

// Where a plan made by make_plan() finds its frames and puts its result.
// A range left null means the plan's own buffer, as for an ordinary Plan.
struct PlanBuffers {
    // sensors x frames frames, sensor-major, each height x width x channels of
    // config.input, packed with no padding. Taken as they are: 8-bit frames
    // always fit; float32 frames must be finite and within [2^-40, 2^40) in
    // magnitude, because the host neither checks nor rescales what it never
    // sees (Plan::run's contract for host frames).
    BufferRange frames;
    // sensors fused images, each height x width x channels float32 (HWC).
    // Needs config.want_fused. Plan::fused() then throws: the image is here.
    // Host float32 frames must then lie within [2^-40, 2^40) in magnitude
    // too: the host cannot scale back an image it never reads, so frames
    // that would need scaling are refused (Error(Numeric) naming the sensor).
    BufferRange fused;
};

// A plan whose cycle can also be recorded into the caller's command buffers
// (record()) and submitted asynchronously (submit()). Plan::run works as
// well: with host frames as usual, or with an empty span when
// buffers.frames is set. Everything else is as Plan (vk/plan.hpp), except
// that skipping (config.skip) and profiling are not available here. The
// buffers must outlive the plan, and be the context's device's (a buffer of
// another device is undefined behaviour, as everywhere in Vulkan). Throws
// Error naming the problem for a range that is too small, misaligned, or
// runs past its buffer's memory requirement.
Plan make_plan(Context& context, const PlanConfig& config, const PlanBuffers& buffers = {});

// Host frames (as Plan::run takes them) into the plan's upload buffer, for a
// cycle recorded or submitted next. Not for a plan with buffers.frames.
void upload(Plan& plan, std::span<const FrameView> frames);

// Appends one cycle of the plan to cmd, a primary command buffer in the
// recording state from a pool of the context's queue family. The cycle
// waits for every earlier command's memory writes (the caller's frames), and
// its writes are visible to every later command and to the host. The plan's
// commands are prerecorded once (a secondary command buffer executed here):
// appending costs the same whatever the method. After the caller's
// submission has completed, call finished() before reading the results; the
// plan must not run again in any way (record, submit, run) while that
// submission is pending, as the cycle uses the plan's buffers.
void record(Plan& plan, VkCommandBuffer cmd);

// The caller's submission holding the cycle record() appended has completed:
// metrics() and fused() read that cycle's results from here on.
void finished(Plan& plan);

// A semaphore the caller's submission waits for (a timeline value, or 0 for
// a binary semaphore) before the plan's cycle starts.
struct SemaphoreWait {
    VkSemaphore semaphore = VK_NULL_HANDLE;
    std::uint64_t value = 0;
    VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
};

// Submits one cycle on the context's queue and returns at once. The cycle
// starts once every wait is met and, when it ends, sets the plan's timeline
// semaphore (timeline()) to the value returned (1, 2, ... per submit). A
// previous submit still pending is waited out first (the plan has one set of
// buffers). The cycle also waits for every command submitted to the same
// queue before it (it may read frames they wrote, and writes the fused image
// they may read); work on other queues that touches the plan's buffers must
// be among the waits. Frames: uploaded before (upload()) or in buffers.frames.
std::uint64_t submit(Plan& plan, std::span<const SemaphoreWait> waits = {});
// The plan's timeline semaphore: the caller's own submissions may wait on it.
VkSemaphore timeline(const Plan& plan);
// Waits on the host for the last submit(); its results are then readable.
void wait(Plan& plan);

// A buffer of the context's device whose memory is shared: allocated here
// for export, or imported from another device's export or from host memory.
// Usable as a PlanBuffers range (range()). Owns its VkBuffer and
// VkDeviceMemory; the Context must outlive it.
class DeviceMemory {
public:
    // bytes of device memory another device or process can import:
    // export_fd() gives it an fd. Needs CallerDevice::external_memory_fd (or
    // an own Context on a device with VK_KHR_external_memory_fd).
    static DeviceMemory allocate_exportable(Context& context, VkDeviceSize bytes);
    // Imports an opaque fd another device exported. bytes: the exporter's
    // allocation size (size() of allocate_exportable() memory); the buffer
    // spans all of it. Both devices must share a driver and device UUID
    // (the opaque fd's rule). On success the fd belongs to Vulkan (do not
    // close it); on failure it is still the caller's.
    static DeviceMemory import_fd(Context& context, int fd, VkDeviceSize bytes);
    // Imports host memory, which must stay valid for this object's life:
    // pointer and bytes must be multiples of host_pointer_alignment().
    static DeviceMemory import_host(Context& context, void* pointer, VkDeviceSize bytes);
    // The device's minImportedHostPointerAlignment (0 without the extension).
    static VkDeviceSize host_pointer_alignment(Context& context);

    // A new fd for this memory, the caller's to close (or to import
    // elsewhere); only for allocate_exportable() memory.
    int export_fd() const;
    BufferRange range() const;  // the buffer: the bytes asked for
    VkDeviceSize size() const;  // the memory's allocation size, which import_fd must be told
    // The host's view where the memory is host-visible (always for
    // import_host), else null.
    void* mapped() const;

    ~DeviceMemory();
    DeviceMemory(DeviceMemory&&) noexcept;
    DeviceMemory& operator=(DeviceMemory&&) noexcept;
    DeviceMemory(const DeviceMemory&) = delete;
    DeviceMemory& operator=(const DeviceMemory&) = delete;

    struct Impl;

private:
    explicit DeviceMemory(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse

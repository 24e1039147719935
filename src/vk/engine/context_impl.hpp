// Context::Impl: the instance, the chosen device, its compute queue and the
// compute pipelines built so far (shared by every Plan of the Context).
#pragma once
#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "vk/engine/api.hpp"
#include "vk/engine/device_profile.hpp"
#include "vk/engine/kernel_interface.hpp"
#include "vk/engine/memory_types.hpp"
#include "vk/engine/pipeline_cache.hpp"
#include "vkfuse/vk/context.hpp"
#include "vkfuse/vk/interop.hpp"

namespace vkfuse {

struct Context::Impl {
    std::unique_ptr<vk::Api> api;
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    std::uint32_t queue_family = 0;
    // The device's properties as the library sees them: its own, or lowered
    // by a simulated profile (vk/engine/device_profile.hpp).
    VkPhysicalDeviceProperties properties{};
    vk::MemoryTypes memory_types;  // every allocation goes through it
    const vk::DeviceProfile* profile = nullptr;  // the simulated profile, if any
    DeviceInfo info;
    bool device_addresses = true;  // bufferDeviceAddress enabled (else every kernel is bound)
    // Storage buffers a bound kernel may have (the set layout's bindings):
    // kMaxKernelBuffers, or fewer where maxPerStageDescriptorStorageBuffers is
    // lower; a kernel with more reaches them through device addresses.
    std::uint32_t bound_buffers = 0;
    bool memory_budget = false;  // VK_EXT_memory_budget offered, and enabled (never on a caller's device)
    bool denorm_preserve = false;  // every kernel asks to keep float32 subnormals (vk/engine/spirv_subnormals.hpp)
    std::uint32_t timestamp_bits = 0;  // the queue's timestampValidBits (0: no timestamp queries); wraps at 2^bits
    bool timestamps() const { return timestamp_bits > 0; }
    // false on a caller's device (vk/interop.hpp): the instance, device and
    // queue are the caller's, and only vkfuse's own objects are destroyed.
    bool owns_device = true;
    bool device_addresses_only = false;  // ContextOptions::device_addresses_only
    FilterArithmetic filter_arithmetic = FilterArithmetic::CompensatedFloat32;  // resolved, never Auto
    KernelBuffers kernel_buffers = KernelBuffers::Bound;                          // resolved, never Auto
    // Shared by all kernels: set 0 of kMaxKernelBuffers storage buffers (the
    // bound variants, shaders/bindings.glsl) and kPushConstantBytes.
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;

    // ContextOptions::pipeline_cache (or VKFUSE_PIPELINE_CACHE): null for none.
    std::unique_ptr<vk::PipelineCache> pipeline_cache;

    std::mutex queue_mutex;  // vkQueueSubmit needs external synchronisation across threads

    std::function<void(const std::string&)> on_validation_message;
    std::atomic<std::uint64_t> validation_messages{0};

    explicit Impl(const ContextOptions& options);
    Impl(const CallerDevice& caller, const ContextOptions& options);  // make_context()
    ~Impl();
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    // The compute pipeline of an embedded shader, built on first use. The
    // specialization words are the values of constant_id 0, 1, ... (32 bits
    // each): one pipeline per shader and distinct values.
    VkPipeline pipeline(const std::string& shader, std::span<const std::uint32_t> specialization = {});
    // The bindings and push-constant size an embedded shader declares (its SPIR-V).
    const vk::KernelInterface& kernel_interface(const std::string& shader);
    // What kernel_interface(shader) answers from now on: the interface of a
    // modified copy of the kernel's SPIR-V, for the test that shows a push
    // block out of step with the C++ side is refused at plan build.
    void use_kernel_interface(const std::string& shader, vk::KernelInterface k);
    // A new pipeline of an embedded shader with another layout, owned by the
    // caller (device probes that bind descriptor sets).
    VkPipeline create_pipeline(const std::string& shader, VkPipelineLayout with_layout,
                               std::span<const std::uint32_t> specialization = {});

    // Compensated float32 without fma (compensated.glsl's SPLIT_PRODUCTS,
    // given to every pipeline as kSplitProductsConstant): decided on the first
    // call, before the first compensated kernel is built, by asking the device
    // whether its fma is fused (vk/engine/fma_probe.hpp); false under float64.
    bool products_split();

    // What the library changed to fit this device (Context::adaptations()).
    void adapted(const std::string& what);
    std::vector<std::string> adaptations() const;
    // A buffer that wanted memory type `wanted` took `taken` (its heap was full).
    void note_fallback(std::uint32_t wanted, std::uint32_t taken);
    // Without device addresses: a fresh range of `bytes` in an address space
    // of the library's own, so that buffers keep distinct addresses for the
    // plan's graph to name them by (vk/engine/buffer.cpp). Never given to a kernel.
    VkDeviceAddress handle_address(VkDeviceSize bytes) {
        return next_handle_address_.fetch_add((bytes + 511) / 256 * 256);
    }
    // Buffers of host memory imported into system memory on a device that
    // has device-local memory (DeviceMemory::import_host on a discrete GPU):
    // a plan reading its frames from one copies them to device-local memory
    // first. Noted by the import, forgotten when it is released.
    void note_system_memory(VkBuffer buffer, bool in_system_memory);
    bool in_system_memory(VkBuffer buffer) const;

private:
    std::mutex products_mutex_;
    bool split_requested_ = false;  // ContextOptions::split_products
    // products_split() once decided (1 split, 0 not), -1 before: atomic, as
    // create_pipeline reads it under the pipelines' lock, not the products'.
    std::atomic<int> split_state_{-1};
    std::atomic<VkDeviceAddress> next_handle_address_{VkDeviceAddress(1) << 40};
    mutable std::mutex adaptations_mutex_;
    std::vector<std::string> adaptations_;  // in the order they happened, each once
    mutable std::mutex system_memory_mutex_;
    std::set<VkBuffer> system_memory_buffers_;
    std::mutex pipelines_mutex_;
    std::map<std::pair<std::string, std::vector<std::uint32_t>>, VkPipeline> pipelines_;
    std::map<std::string, vk::KernelInterface> interfaces_;

    void create_instance(bool validation, bool synchronization_validation);
    void choose_device(int index);
    // The profile ContextOptions or VKFUSE_DEVICE_PROFILE names, applied to
    // the chosen device's limits, memory and features.
    void apply_profile(const std::string& name);
    void choose_filter_arithmetic(FilterArithmetic wanted);
    void choose_kernel_buffers(KernelBuffers wanted);
    void create_device();
    void create_layout();
    // The pipeline cache the options or the environment name, if any.
    void open_pipeline_cache(const std::string& path);
    void release();  // destroys every Vulkan object; safe to call twice
};

// Maximum push-constant bytes any vkfuse kernel uses (the guaranteed minimum).
inline constexpr std::uint32_t kPushConstantBytes = 128;
// Most buffers one kernel binds (shaders/bindings.glsl).
inline constexpr std::uint32_t kMaxKernelBuffers = 8;

namespace vk {

// The library's access to a Context's device (Context::impl() is private: no
// Vulkan type is part of ordinary use).
struct ContextAccess {
    static Context::Impl& of(Context& context) { return context.impl(); }
    static Context adopt(std::unique_ptr<Context::Impl> impl) { return Context(std::move(impl)); }
};

}  // namespace vk

}  // namespace vkfuse

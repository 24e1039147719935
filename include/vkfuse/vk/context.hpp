// vkfuse/vk/context.hpp - a Vulkan device, opened once and shared by plans.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vkfuse {
namespace vk {
struct ContextAccess;
}

struct DeviceInfo {
    int index = 0;            // position in the loader's enumeration
    std::string name;         // "llvmpipe (LLVM 15.0.6, 256 bits)", "NVIDIA H100 ..."
    std::string driver;       // driver name and info
    std::string type;         // "cpu", "integrated", "discrete", "virtual", "other"
    std::string api_version;  // "1.3.230"
    bool usable = false;      // meets vkfuse's needs (Vulkan 1.2, a compute queue)
    std::string why_not;      // when !usable, the missing capability
    bool fp16_storage = false;  // 16-bit storage buffers (storageBuffer16BitAccess): Precision::Fp16Storage
    bool float64 = false;       // double arithmetic in shaders: FilterArithmetic::Float64
    // Kernels keep float32 subnormals: a CPU device does, a GPU that offers
    // shaderDenormPreserveFloat32 is asked to. Elsewhere a GPU may flush them
    // to zero, and a plan keeps float32 frames that lie far below their
    // background further from subnormals (a narrower range of the two it
    // can fuse, beyond which it says so).
    bool float32_subnormals = false;
    // bufferDeviceAddress: kernels may reach buffers by address (plans whose
    // one sensor exceeds a binding's range need it; without it every kernel binds).
    bool device_addresses = false;
    // Memory shared with other devices and the host (vk/interop.hpp, DeviceMemory).
    bool external_memory_fd = false;    // VK_KHR_external_memory_fd
    bool external_memory_host = false;  // VK_EXT_external_memory_host
};

// How the wavelet filters accumulate an output before rounding it to float
// once. Both meet the same tolerances (float64 a little closer to the double
// reference; outputs may differ in the last bits); they differ in cost: a
// double fma per tap, or about ten float operations per tap.
enum class FilterArithmetic {
    Auto,                // Float64 on CPU devices that have it (lavapipe), else CompensatedFloat32
    Float64,             // a double accumulator (needs DeviceInfo::float64)
    CompensatedFloat32,  // Dot2: a float sum and its error term (any device)
};
std::string_view to_string(FilterArithmetic);  // "auto", "float64", "compensated float32"
// The to_string name, with '-' accepted for its space ("compensated-float32",
// how VKFUSE_FILTER_ARITHMETIC spells it); nullopt for any other text.
std::optional<FilterArithmetic> parse_filter_arithmetic(std::string_view text);

// How a kernel reaches the buffers a plan gives it. Every kernel is built
// both ways from one list of its buffers (shaders/bindings.glsl), and both
// give the same bits.
enum class KernelBuffers {
    Auto,       // VKFUSE_KERNEL_BUFFERS in the environment when set, else Addresses on a CPU device that
                // has them (lavapipe, where they are the faster path), else Bound
    Bound,      // descriptor bindings; a kernel with more buffers than a stage may bind takes addresses
    Addresses,  // 64-bit device addresses in the push constants (needs bufferDeviceAddress)
};
std::string_view to_string(KernelBuffers);  // "auto", "bound", "addresses"
std::optional<KernelBuffers> parse_kernel_buffers(std::string_view text);

struct ContextOptions {
    int device_index = -1;    // -1: the best usable device (discrete > integrated > cpu)
    bool validation = false;  // enable VK_LAYER_KHRONOS_validation (error if absent)
    // With validation: also the layer's synchronization validation, which
    // reports a missing or too weak barrier as a hazard even where the device
    // (lavapipe runs a submit's dispatches in order) forgives it. Slower; the
    // tests run with it.
    bool synchronization_validation = false;
    // Receives every validation-layer message (errors and warnings) when
    // validation is on. Tests fail on any message of type VALIDATION.
    std::function<void(const std::string&)> on_validation_message;
    // Kernels reach their buffers through descriptor bindings; a plan whose
    // buffers exceed what one binding may span (the device's
    // maxStorageBufferRange) runs in blocks of sensors that fit, and uses
    // device addresses only where not even one sensor fits. true: every plan
    // uses device addresses as one chain, never blocks (to test or compare
    // that path on any plan); kernel_buffers is then Addresses.
    bool device_addresses_only = false;
    // Which way kernels reach the buffers they are given (a plan's blocks
    // are the same either way). Throws Error(Device) for Addresses on a device
    // without bufferDeviceAddress.
    KernelBuffers kernel_buffers = KernelBuffers::Auto;
    // Auto: VKFUSE_FILTER_ARITHMETIC in the environment when set (auto,
    // float64, compensated-float32: how tests run every kernel in a GPU's
    // arithmetic on lavapipe), else Float64 on CPU devices that have it.
    FilterArithmetic filter_arithmetic = FilterArithmetic::Auto;
    // Compensated float32 takes each product's rounding error from fma, which
    // Vulkan does not promise to be fused: the context asks the device once
    // and, where it is not, takes the error from Dekker's split (about 17
    // float operations instead of 2). true: the split on any device (to test
    // or compare that path).
    bool split_products = false;
    // A simulated device profile (device_profile_names()): the device's limits,
    // memory and features seen as those of a GPU class it is not, so that
    // what vkfuse does on that class runs here (lavapipe in tests). A profile
    // only lowers what the device offers. "": VKFUSE_DEVICE_PROFILE in the
    // environment when set, else none. Throws Error(InvalidArgument) for an
    // unknown name.
    std::string device_profile;
    // A file the compute pipelines are cached in across runs: read at start
    // where its header names this device and driver (else ignored, as is a
    // file over 64 MiB) and written back whole when the context ends, if it
    // grew. For drivers that keep no cache of their own. "":
    // VKFUSE_PIPELINE_CACHE in the environment when set, else none. Throws
    // Error(Io) when its directory does not exist or it is not a regular file.
    std::string pipeline_cache;
};

// The simulated device profiles, in the order `vkfuse info` lists them:
// discrete-no-rebar, phone, no-device-address.
std::vector<std::string> device_profile_names();

// Throws the Error(InvalidArgument) a Context would for the environment's
// VKFUSE_DEVICE_PROFILE, VKFUSE_FILTER_ARITHMETIC or VKFUSE_KERNEL_BUFFERS, without opening a
// device: a program checks them before its first output.
void check_vulkan_environment();

// One memory heap as vkfuse sees it (a simulated profile's, where one is in use).
struct MemoryHeap {
    std::uint64_t bytes = 0;           // the heap's size
    bool device_local = false;
    bool host_visible = false;         // some memory type of the heap is host-visible
    std::uint64_t vkfuse_bytes = 0;    // allocated by this context now
    // VK_EXT_memory_budget, where the device has it (and no profile is
    // simulated): what the process may use of the heap, and uses, now.
    std::optional<std::uint64_t> budget, usage;
};

// Owns a VkInstance, one VkDevice and its compute queue. Cheap to move, not
// copyable; several Contexts may live in one process, and one Context may be
// shared by threads (pipeline creation and queue submission are locked). Throws Error(Device)
// when no loader, no device, or no usable device exists.
class Context {
public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(Context&&) noexcept;
    Context& operator=(Context&&) noexcept;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& device() const;
    // The filter arithmetic in use: Float64 or CompensatedFloat32, never Auto.
    FilterArithmetic filter_arithmetic() const;
    // How kernels reach their buffers: Bound or Addresses, never Auto.
    KernelBuffers kernel_buffers() const;
    // Compensated float32 with products' errors from Dekker's split (the
    // device's fma is not fused, or ContextOptions::split_products); false
    // under Float64.
    bool splits_products() const;
    // Every memory heap, with what this context has allocated from each and,
    // with VK_EXT_memory_budget, the process's budget and usage: where a
    // plan's buffers went (Context::adaptations() says when a heap was full).
    std::vector<MemoryHeap> memory_heaps() const;
    // The simulated device profile in use, "" for none.
    std::string device_profile() const;
    // What vkfuse changed to fit this device, one sentence each, in the order
    // it happened: the profile, kernels moved to device addresses, a full
    // memory heap's buffers placed in another, products split. Empty where
    // nothing needed changing.
    std::vector<std::string> adaptations() const;
    // The pipeline cache file in use and what it gave at start ("PATH: loaded
    // N bytes", "PATH: starts empty (why)"); "" for none.
    std::string pipeline_cache() const;
    // Number of validation messages seen so far (0 unless validation is on).
    std::uint64_t validation_message_count() const;

    struct Impl;

private:
    friend struct vk::ContextAccess;  // the library's own way to its device
    explicit Context(std::unique_ptr<Impl> impl);  // on a caller's device (vk/interop.hpp)
    Impl& impl() { return *impl_; }
    std::unique_ptr<Impl> impl_;
};

// Which engine computes: the Vulkan path, the CPU reference, or Auto: the
// Vulkan path where a usable device exists, else the CPU reference.
enum class Backend { Cpu, Vulkan, Auto };
std::string_view to_string(Backend);                           // "cpu", "vulkan", "auto"
std::optional<Backend> parse_backend(std::string_view text);  // nullopt for any other text

// The Context `choice` asks for, or nullopt for the CPU reference path. Auto
// falls back to the CPU when no usable device exists, with the reason in
// *fallback_reason (when given); Vulkan then throws Error(Device)
// "<subject> vulkan: no usable Vulkan device (<reason>)", subject naming the
// option ("--backend", "backend").
std::optional<Context> open_backend(Backend choice, std::string_view subject,
                                    std::string* fallback_reason = nullptr);

// Whether the Vulkan validation layer (VK_LAYER_KHRONOS_validation, Debian's
// vulkan-validationlayers) is installed: what ContextOptions::validation
// needs. false also where no Vulkan loader exists.
bool validation_layer_installed();

// Lists the Vulkan devices without opening one. Throws Error(Device) if the
// loader is missing; returns an empty list if it finds no device.
std::vector<DeviceInfo> list_devices();

}  // namespace vkfuse

// vkfuse info: the Vulkan devices this machine offers and which one auto uses.
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::cli {
namespace {

constexpr CommandSpec kSpec{
    "info",
    "list the Vulkan devices and say which one --backend auto uses",
    "vkfuse info",
    "Lists every Vulkan device the loader reports (index, name, driver, type, API\n"
    "version, whether vkfuse can use it, whether it has the 16-bit storage that\n"
    "Precision::Fp16Storage needs, the doubles of float64 filter arithmetic, and\n"
    "the memory sharing of vkfuse/vk/interop.hpp: fds between devices, host memory)\n"
    "and the device --backend auto picks, with the filter arithmetic it uses and\n"
    "what vkfuse adapted to fit it. Then the simulated device profiles, which\n"
    "VKFUSE_DEVICE_PROFILE=NAME applies to any command (the device seen with the\n"
    "limits and memory of that GPU class). VKFUSE_PIPELINE_CACHE=FILE keeps the\n"
    "compiled kernels in FILE across runs (for drivers without a cache of their own).\n"
    "Without a Vulkan loader or device it says so: the CPU reference path is used.",
    {},
    "vkfuse info",
};

void print_device(const DeviceInfo& d) {
    std::string extras;
    if (d.usable && d.fp16_storage) extras += "fp16 storage";
    if (d.usable && d.float64) extras += extras.empty() ? "float64" : ", float64";
    // What vkfuse/vk/interop.hpp's shared memory needs.
    if (d.usable && d.float32_subnormals) extras += extras.empty() ? "float32 subnormals" : ", float32 subnormals";
    if (d.usable && d.external_memory_fd) extras += extras.empty() ? "memory fd" : ", memory fd";
    if (d.usable && d.external_memory_host) extras += extras.empty() ? "host memory" : ", host memory";
    if (d.usable && !d.device_addresses) extras += extras.empty() ? "no device addresses" : ", no device addresses";
    if (!extras.empty()) extras = " (" + extras + " too)";
    std::printf("  [%d] %s\n      type %s, driver %s, Vulkan %s: %s%s%s\n", d.index, d.name.c_str(), d.type.c_str(),
                d.driver.c_str(), d.api_version.c_str(), d.usable ? "usable" : "not usable: ",
                d.usable ? "" : d.why_not.c_str(), extras.c_str());
}

// Opens the device exactly as --backend auto would, so the answer cannot drift
// from what fuse and metrics actually do.
void print_auto_choice() {
    try {
        Context context;
        const DeviceInfo& d = context.device();
        std::printf("--backend auto uses device [%d] %s, wavelet filters accumulating in %s, kernel buffers %s\n",
                    d.index, d.name.c_str(), to_string(context.filter_arithmetic()).data(),
                    to_string(context.kernel_buffers()) == "bound" ? "bound" : "through device addresses");
        context.splits_products();  // asks the device about fma now, so that its answer is listed
        for (const std::string& what : context.adaptations()) std::printf("  adapted: %s\n", what.c_str());
        if (const std::string cache = context.pipeline_cache(); !cache.empty())
            std::printf("  pipeline cache: %s\n", cache.c_str());
        const auto mib = [](std::uint64_t bytes) { return static_cast<unsigned long long>(bytes >> 20); };
        const std::vector<MemoryHeap> heaps = context.memory_heaps();
        for (std::size_t h = 0; h < heaps.size(); ++h) {
            const MemoryHeap& m = heaps[h];
            std::printf("  memory heap %zu: %s%s, %llu MiB", h, m.device_local ? "device-local" : "system",
                        m.host_visible ? " host-visible" : "", mib(m.bytes));
            if (m.budget) std::printf(", budget %llu MiB, in use %llu MiB", mib(*m.budget), mib(m.usage.value_or(0)));
            std::printf("\n");
        }
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::Device) throw;
        std::printf("--backend auto uses the CPU reference path (%s)\n", e.what());
    }
}

void print_profiles() {
    std::string names;
    for (const std::string& name : device_profile_names()) names += (names.empty() ? "" : ", ") + name;
    std::printf("device profiles: %s\n", names.c_str());
}

int run(const Args& args) {
    if (!args.operands().empty()) args.usage_error("unexpected operand " + args.operands().front());
    std::vector<DeviceInfo> devices;
    try {
        devices = list_devices();
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::Device) throw;
        std::printf("No Vulkan loader (%s): the CPU reference path will be used.\n", e.what());
        return 0;
    }
    if (devices.empty()) {
        std::printf("No Vulkan device found: the CPU reference path will be used.\n");
        return 0;
    }
    std::printf("Vulkan devices:\n");
    for (const DeviceInfo& d : devices) print_device(d);
    print_auto_choice();
    print_profiles();
    return 0;
}

}  // namespace

const Command info_command{kSpec, run};

}  // namespace vkfuse::cli

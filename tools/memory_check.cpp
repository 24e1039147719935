#include "memory_check.hpp"

#include <algorithm>
#include <map>
#include <tuple>

#include "core/method_table.hpp"
#include "io/memory_available.hpp"
#include "vk/plan/method_recorders.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;
constexpr double kCpuProcess = 32 * kMiB;
constexpr double kVulkanProcess = 192 * kMiB;

// In images of one frame's size f: the frames as read and in double, the
// result, and what the method's rows add (its reference's transforms on the
// CPU; its intermediates on the device).
double cpu_fuse(double f, int k, Method m) {
    const core::MethodInfo& row = core::method_info(m);
    return f * (k * (3.0 + row.reference_images_per_frame) + 4.0 + row.reference_images_fixed) + kCpuProcess;
}

double vulkan_fuse(double f, int k, Method m) {
    const vk::MethodRecorder& row = vk::method_recorder(m);
    return f * (k * (3.0 + row.floats_per_input) + 6.0 + row.floats_per_output) + kVulkanProcess;
}

std::uint64_t bytes(double b) { return b >= 1.8e19 ? UINT64_MAX : std::uint64_t(b); }

}  // namespace

std::uint64_t fuse_memory_need(const std::vector<io::ImageHeader>& inputs, Method method, Backend backend) {
    if (inputs.empty()) return 0;
    const double f = double(inputs.front().image_bytes());
    const int frames = int(inputs.size());
    double decode = 0;
    for (const io::ImageHeader& h : inputs) decode = std::max(decode, double(h.decode_bytes));
    double need = 0;
    if (backend != Backend::Vulkan) need = std::max(need, cpu_fuse(f, frames, method));
    if (backend != Backend::Cpu) need = std::max(need, vulkan_fuse(f, frames, method));
    return bytes(need + decode);
}

std::uint64_t metrics_memory_need(const std::vector<io::ImageHeader>& inputs, const io::ImageHeader* background,
                                  Backend backend) {
    const double bg = background ? double(background->image_bytes()) : 0.0;
    double all = 0, largest = 0, largest_decode = background ? double(background->decode_bytes) : 0.0;
    std::map<std::tuple<int, int, int>, double> shapes;
    for (const io::ImageHeader& h : inputs) {
        all += double(h.image_bytes());
        largest = std::max(largest, double(h.image_bytes()));
        largest_decode = std::max(largest_decode, double(h.decode_bytes));
        shapes[{h.height, h.width, h.channels}] = double(h.image_bytes());
    }
    double plans = 0;
    for (const auto& [shape, f] : shapes) plans += 3.5 * f;
    double need = 0;
    if (backend != Backend::Vulkan) need = std::max(need, 3 * bg + all + 2 * largest + kCpuProcess);
    if (backend != Backend::Cpu) need = std::max(need, bg + all + plans + kVulkanProcess);
    return bytes(need + largest_decode);
}

static std::string names(const std::vector<std::string>& paths) {
    std::string text;
    constexpr std::size_t kNamed = 6;
    for (std::size_t i = 0; i < paths.size() && i < kNamed; ++i) text += (i ? ", " : "") + paths[i];
    if (paths.size() > kNamed) text += " and " + std::to_string(paths.size() - kNamed) + " more";
    return text;
}

void require_memory(const std::vector<std::string>& paths, std::string_view doing, std::uint64_t need) {
    const auto available = io::available_memory();
    if (!available || need <= available->bytes) return;
    // Enough digits that the two figures differ: never "needs 4.0 GiB, 4.0 GiB available".
    int decimals = 1;
    while (decimals < 3 && io::memory_text(double(need), decimals) == io::memory_text(double(available->bytes), decimals))
        ++decimals;
    throw Error(ErrorKind::InvalidArgument, names(paths) + ": " + std::string(doing) + " needs about " +
                                                io::memory_text(double(need), decimals) + " of memory, " +
                                                io::memory_text(double(available->bytes), decimals) + " available (" +
                                                available->source + ")");
}

void out_of_memory(const std::vector<std::string>& paths, std::string_view doing, std::uint64_t need) {
    std::string available = "the available memory unknown";
    try {
        if (auto a = io::available_memory()) available = io::memory_text(double(a->bytes)) + " available (" + a->source + ")";
    } catch (const Error&) {
    }
    throw Error(ErrorKind::InvalidArgument, names(paths) + ": out of memory while " + std::string(doing) + " (about " +
                                                io::memory_text(double(need)) + " estimated, " + available + ")");
}

}  // namespace vkfuse::cli

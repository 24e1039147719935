#include "memory.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "inputs.hpp"
#include "vk/method_recorders.hpp"

namespace vkfuse::bench {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
constexpr double kProcessBytes = 0.25 * kGiB;  // the process itself: Vulkan driver, LLVM (lavapipe), Python peer


}  // namespace

double estimated_bytes(const Cell& c) {
    const double frame = double(c.size.width) * c.size.height * 3 * sizeof(float);
    const double inputs = frame * c.frames * c.sensors;
    const double outputs = frame * c.sensors;
    const double scenes = std::min(c.sensors, kMaxScenes);
    const double checked = std::min(c.sensors, 4);
    // One reference computation at its peak: K frames in double, their
    // transforms (about 1.5 times their size) and the fused result.
    const double reference = 2 * frame * (2.5 * c.frames + 2);
    // Host: generated frames and backgrounds, one reference computation, the
    // checked sensors' reference results kept (double).
    const double host = kProcessBytes + frame * scenes * (c.frames + 1) + reference + 2 * frame * checked;
    // The CPU backend: its own computation, its backgrounds and kept results in double.
    if (c.backend == Backend::Cpu) return host + reference + 2 * frame * (scenes + checked);
    // Upload + planar input, the method's intermediates (its Vulkan row) and
    // fused planes, readback + backgrounds, and the fused images Plan::fused()
    // keeps on the host.
    const vk::MethodRecorder& m = vk::method_recorder(c.method.method);
    return host + 2 * inputs + m.floats_per_input * inputs + (m.floats_per_output + 1) * outputs + 3 * outputs;
}

double memory_budget(double limit_gib) {
    if (limit_gib > 0) return limit_gib * kGiB;
    std::ifstream meminfo("/proc/meminfo");
    std::string line;
    while (std::getline(meminfo, line)) {
        std::istringstream fields(line);
        std::string key;
        double kib = 0;
        if (fields >> key >> kib && key == "MemAvailable:") return 0.8 * kib * 1024.0;
    }
    return 4 * kGiB;
}

}  // namespace vkfuse::bench

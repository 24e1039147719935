#include "memory.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "inputs.hpp"

namespace vkfuse::bench {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
constexpr double kProcessBytes = 0.25 * kGiB;  // the process itself: Vulkan driver, LLVM (lavapipe), Python peer

// Device floats per input float and per output float beyond upload and input
// planes, from the graph builders in src/vk: the wavelet keeps every level's
// coefficient blocks for all frames plus a scratch plane set and every level's
// fused blocks; the Laplacian a Gaussian pyramid (1/3 more) and fused levels.
struct Intermediates {
    double per_input;
    double per_output;
};

Intermediates intermediates(Method m) {
    switch (m) {
        case Method::Wavelet: return {2.4, 3.4};
        case Method::Laplacian: return {0.4, 1.4};
        default: return {0.0, 1.0};
    }
}

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
    const auto im = intermediates(c.method.method);
    // Upload + planar input, intermediates, readback + backgrounds, and the
    // fused images Plan::fused() keeps on the host.
    return host + 2 * inputs + im.per_input * inputs + im.per_output * outputs + 3 * outputs;
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

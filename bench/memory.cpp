#include "memory.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "inputs.hpp"

namespace vkfuse::bench {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

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
    // Host: generated frames and backgrounds, the reference (double) of up to
    // four checked sensors with its own pyramid, the fused images read back.
    const double host = frame * scenes * (c.frames + 1) + 4 * 2 * frame * (2 * c.frames + 4) + outputs;
    if (c.backend == Backend::Cpu) return host + 2 * frame * (2 * c.frames + 4);
    const auto im = intermediates(c.method.method);
    // Upload + planar input, intermediates, readback + backgrounds.
    return host + 2 * inputs + im.per_input * inputs + im.per_output * outputs + 2 * outputs;
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

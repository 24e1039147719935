#include <algorithm>
#include <map>

#include "backends.hpp"
#include "vkfuse/reference.hpp"

namespace vkfuse::bench {
namespace {

struct SensorResult {
    ImageD fused;
    Metrics metrics;
};

}  // namespace

CellResult measure_cpu(const Cell& cell, const Inputs& in, const std::vector<Expected>& expected,
                       const RunPolicy& policy) {
    CellResult r;
    r.cell = cell;
    r.device = kCpuDevice;
    const FusionSpec spec = cell.fusion();
    // Backgrounds are converted once, as Plan::set_background does on the GPU
    // path (per scene: sensors that share a scene share its background).
    std::vector<ImageD> backgrounds;
    for (int s = 0; s < std::min(cell.sensors, kMaxScenes); ++s) backgrounds.push_back(convert<double>(in.background(s)));
    std::map<int, SensorResult> kept;  // the checked sensors' results of the last cycle
    for (const auto& e : expected) kept[e.sensor];
    std::vector<ImageD> frames(std::size_t(cell.frames));
    r.timing = time_cycles(policy, [&] {
        for (int s = 0; s < cell.sensors; ++s) {
            for (int k = 0; k < cell.frames; ++k) frames[std::size_t(k)] = convert<double>(in.frame(s, k));
            ImageD fused = fuse_reference(frames, spec);
            const Metrics m = metrics_reference(fused, &backgrounds[std::size_t(in.scene_of(s))]);
            if (auto it = kept.find(s); it != kept.end()) it->second = {std::move(fused), m};
        }
    });
    for (const auto& e : expected) {
        const SensorResult& got = kept[e.sensor];
        r.error.add(got.fused, e.fused);
        r.metric_error.add(got.metrics, e.metrics);
        r.metric_error_own_image.add(got.metrics, e.metrics);  // its own image is the reference
    }
    r.checked_sensors = int(expected.size());
    return r;
}

}  // namespace vkfuse::bench

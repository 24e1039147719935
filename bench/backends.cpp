#include "backends.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include "vkfuse/core/reference.hpp"
#include "vkfuse/vk/plan.hpp"

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

namespace {

PlanConfig plan_config(const Cell& cell, bool profile) {
    PlanConfig cfg;
    cfg.fusion = cell.fusion();
    cfg.height = cell.size.height;
    cfg.width = cell.size.width;
    cfg.channels = 3;
    cfg.frames = cell.frames;
    cfg.sensors = cell.sensors;
    cfg.input = PixelType::F32;
    cfg.want_fused = true;
    cfg.metrics = MetricSet::all();
    cfg.profile = profile;
    cfg.precision = cell.precision;
    return cfg;
}

// Per-stage medians over the runs, in the plan's stage order.
std::vector<StageTime> stage_medians(const std::vector<std::vector<KernelTime>>& runs) {
    std::vector<StageTime> out;
    if (runs.empty()) return out;
    for (std::size_t i = 0; i < runs.front().size(); ++i) {
        std::vector<double> ms;
        for (const auto& run : runs) ms.push_back(run[i].ms);
        out.push_back({runs.front()[i].name, median(ms)});
    }
    return out;
}

}  // namespace

CellResult measure_vulkan(Context& context, const Cell& cell, const Inputs& in, const std::vector<Expected>& expected,
                          const RunPolicy& policy, bool profile) {
    CellResult r;
    r.cell = cell;
    r.device = context.device().name;
    r.driver = context.device().driver;
    const auto start = std::chrono::steady_clock::now();
    Plan plan(context, plan_config(cell, profile));
    for (int s = 0; s < cell.sensors; ++s) plan.set_background(s, FrameView::of(in.background(s)));
    r.plan_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const std::vector<FrameView> views = in.views();
    std::vector<std::vector<KernelTime>> profiles;
    r.timing = time_cycles(
        policy,
        [&] {
            plan.run(views);
            // fused() copies the image out of the readback buffer: part of the cycle.
            for (int s = 0; s < cell.sensors; ++s) {
                plan.fused(s);
                plan.metrics(s);
            }
        },
        [&] {
            if (profile) profiles.push_back(plan.profile());
        });
    r.stages = stage_medians(profiles);
    for (const auto& e : expected) {
        r.error.add(plan.fused(e.sensor), e.fused);
        r.metric_error.add(plan.metrics(e.sensor), e.metrics);
        const ImageD background = convert<double>(in.background(e.sensor));
        r.metric_error_own_image.add(plan.metrics(e.sensor),
                                     metrics_reference(convert<double>(plan.fused(e.sensor)), &background));
    }
    r.checked_sensors = int(expected.size());
    // Every frame up, every fused image and the metric totals (8 floats) down.
    r.bytes_per_cycle = double(in.frame_bytes()) * (cell.frames + 1) * cell.sensors + 32.0 * cell.sensors;
    return r;
}

Timing time_empty_cycle(Context& context, const RunPolicy& policy) {
    PlanConfig cfg;
    cfg.fusion.method = Method::Brovey;
    cfg.height = cfg.width = 4;
    cfg.channels = 3;
    cfg.frames = 2;
    cfg.input = PixelType::F32;
    cfg.metrics = MetricSet();
    Plan plan(context, cfg);
    Image frame(4, 4, 3);
    std::fill(frame.data.begin(), frame.data.end(), 0.5f);
    const std::vector<FrameView> views{FrameView::of(frame), FrameView::of(frame)};
    return time_cycles(policy, [&] {
        plan.run(views);
        plan.fused(0);
    });
}

}  // namespace vkfuse::bench

// vkfuse/vk/plan.hpp - the GPU hot path: plan once, run every sensor cycle.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/core/skip.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse {
namespace vk {
struct PlanAccess;
}

// How a plan stores the planes it keeps on the device between kernels
// (unpacked frames, pyramid levels, wavelet coefficients, fused planes).
// Arithmetic is float32 either way, and frames, backgrounds, metrics and the
// fused image read back are float32. Fp16Storage halves the bytes each kernel
// moves, which is what a memory-bound GPU spends its time on, at about 1e-3
// relative error (vkfuse-bench reports it per cell); it is never the default
// and needs DeviceInfo::fp16_storage, else Plan throws Error(Device). Planes
// then hold magnitudes up to 65504: where a value overflowed (inputs far
// outside [0, 1]; float32 frames beyond 2^40 are scaled down first, see
// run()), fused() and metrics() throw Error(Numeric) instead of returning Inf
// or NaN.
enum class Precision { Fp32, Fp16Storage };
std::string_view to_string(Precision);

struct PlanConfig {
    FusionSpec fusion;      // ignored when fuse is false
    int height = 0;
    int width = 0;
    int channels = 3;       // 1 or 3
    int frames = 2;         // K: frames fused per sensor per cycle
    int sensors = 1;        // S: sensors served by one submit
    PixelType input = PixelType::F32;
    bool want_fused = true;     // read back the fused image of every sensor
    // The metrics computed per sensor (none: no metric pass). BackgroundDiff
    // needs each sensor's background (set_background) before run().
    MetricSet metrics = {Metric::Sharpness, Metric::Contrast};
    bool profile = false;       // per-kernel GPU timestamps (Plan::profile)
    Precision precision = Precision::Fp32;
    // false: nothing is fused; each sensor's one frame (frames = 1) is read
    // back as it is and scored (what `vkfuse metrics` does).
    bool fuse = true;
    // Skipping sensors whose frames did not change (docs/spec.md,
    // "Skipping"): needs fuse and 8-bit frames, and a reference per sensor
    // (Plan::set_skip_reference) before run().
    SkipConfig skip = {};
    // Cycles the plan can have on the device at once: 1 or 2. With 2 the plan
    // holds two sets of per-cycle buffers and command buffers (twice the
    // device memory), so the upload and read-back of one cycle overlap the
    // device's work on the other (Plan::submit). A skipping plan takes 1: it
    // keeps its references and held results once, and under skip static or
    // tiles its host decides between detection and fusion.
    int cycles_in_flight = 1;
};

// Time one kernel (or a group of dispatches) took on the device in the last run.
struct KernelTime {
    std::string name;
    double ms = 0;
};

// Everything for one (method, shape, K, S, metrics) is created here once:
// pipelines, device buffers and one command buffer recorded at construction
// (one per cycle in flight). run() copies the frames into the upload buffer,
// submits that command buffer once, waits, and exposes what was asked for;
// submit() and collect() split that round trip so that two cycles overlap. A
// Plan is used by one thread at a time; plans of one Context may run on
// different threads at once. The Context must outlive its plans. Throws Error
// on invalid configuration or device failure.
class Plan {
public:
    Plan(Context& context, const PlanConfig& config);
    ~Plan();
    Plan(Plan&&) noexcept;
    Plan& operator=(Plan&&) noexcept;
    Plan(const Plan&) = delete;
    Plan& operator=(const Plan&) = delete;

    const PlanConfig& config() const;

    // Background frame of one sensor (shape height x width x channels, U8 or
    // F32 whatever config().input is: a background model is a float mean).
    // Needed before run() when metrics has BackgroundDiff. Throws Error(Numeric)
    // for NaN or Inf, and in a U8 plan for one whose largest magnitude is
    // below 2^-64 (8-bit frames are never scaled, see run()).
    void set_background(int sensor, const FrameView& background);

    // The scene a skipping plan compares sensor's frames with (core/skip.hpp):
    // K means and deviations of the frames' shape. The reference is fused
    // here, once, with the double-precision reference path: that image is the
    // result of every cycle the sensor is idle. Throws Error naming the sensor
    // for a wrong count, shape or a non-finite value.
    void set_skip_reference(int sensor, const SkipReference& reference);

    // frames: sensors x frames views, sensor-major (sensor s, frame k at
    // s * frames + k), each height x width x channels of type config().input.
    // F32 frames may hold any finite magnitude, subnormal to FLT_MAX: where a
    // sensor's frames (and background) lie outside [2^-40, 2^40) they are
    // multiplied by a power of two on the way to the device and its results
    // by its inverse on the way back (docs/architecture.md, "Magnitudes").
    // NaN or Inf in a frame: Error(Numeric) naming it, as for the reference.
    // A plan reading its frames from a device buffer (vk/interop.hpp,
    // PlanBuffers::frames) takes an empty span.
    void run(std::span<const FrameView> frames);

    // A pipelined cycle: submit() checks and uploads the frames (as run())
    // and starts their cycle on the device without waiting for it; collect()
    // waits for the oldest cycle submitted and not yet collected, and
    // fused(), metrics(), skip_outcome() and profile() then read its results
    // until the next submit(). With config().cycles_in_flight 2 a sensor loop
    // submits cycle c + 1, collects cycle c and reads it while c + 1 runs.
    // At most cycles_in_flight cycles are submitted and not collected:
    // submit() beyond that, collect() with none, or a result read after a
    // submit() throws Error(InvalidArgument). run() collects every cycle
    // still in flight first (their results are dropped). Under skip idle the
    // device decides which sensors to fuse within the cycle's one submit;
    // under static or tiles (and for frames whose sensors do not start on
    // 4-byte boundaries) submit() runs the detection and the host's decision
    // before it submits the fusion.
    void submit(std::span<const FrameView> frames);
    void collect();
    int in_flight() const;  // cycles submitted and not collected

    // Results of the last run(). Error(Numeric) where a fused value lies
    // beyond float32's range (the reference cannot store it either) or the
    // device computed a non-finite value: never Inf, NaN or a wrong number.
    const Image& fused(int sensor) const;  // requires want_fused
    Metrics metrics(int sensor) const;     // requires metrics not empty
    // Requires profile: each stage's GPU time in the last run, in recording
    // order, every sensor's work in it (empty before a fusing run).
    std::vector<KernelTime> profile() const;
    SkipOutcome skip_outcome(int sensor) const;  // idle false, fractions 1 when skip is off
    // Cycles whose fusion was submitted so far: one per run() or submit(),
    // whatever the sensor count. A skipping plan counts only the cycles in
    // which some sensor changed: where every sensor was idle it submitted
    // its change detection alone, or (skip idle) a command buffer whose
    // fusion dispatched nothing.
    std::uint64_t submits() const;

    struct Impl;

private:
    friend struct vk::PlanAccess;               // make_plan() and the interop calls (vk/interop.hpp)
    explicit Plan(std::unique_ptr<Impl> impl);  // the library's internal plan kinds
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse

// rig/engine.hpp - what fuses a cycle: the GPU Plan or the CPU reference path,
// behind one interface so the rig runs with or without a Vulkan device.
#pragma once
#include <cstdint>
#include <memory>
#include <span>

#include "vkfuse/core/image.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/vk/context.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::rig {

class Engine {
public:
    virtual ~Engine() = default;
    // The background background_diff compares with (kept only when the
    // engine computes that metric).
    virtual void set_background(int sensor, const Image& background) = 0;
    virtual void set_skip_reference(int sensor, const SkipReference& reference) = 0;
    // frames sensor-major, as Plan::run; submit() and collect() as Plan's
    // (the CPU path fuses in submit(), and keeps 1 cycle in flight).
    virtual void run(std::span<const FrameView> frames) = 0;
    virtual void submit(std::span<const FrameView> frames) = 0;
    virtual void collect() = 0;
    virtual int cycles_in_flight() const = 0;
    virtual const Image& fused(int sensor) = 0;
    virtual Metrics metrics(int sensor) = 0;
    virtual SkipOutcome skip_outcome(int sensor) = 0;
    virtual std::uint64_t submits() const = 0;
};

// A Plan on context, or the CPU reference path when context is null (config
// as for a Plan; metrics and skip are honoured the same
// way: the CPU path detects change with core/skip.hpp's reference, the same
// statistic in double precision).
std::unique_ptr<Engine> make_engine(Context* context, const PlanConfig& config);

// A borrowed frame as a double image (v / 255 for 8-bit).
ImageD to_double(const FrameView& view);

}  // namespace vkfuse::rig

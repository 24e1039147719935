// vkfuse/rig/background.hpp - the background model: per illumination, the mean of
// N frames taken with nothing touching the gel (the paper averages 100). The
// difference-with-background metric compares a frame against it.
#pragma once
#include <memory>
#include <span>

#include "vkfuse/core/image.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse {

// Averages exactly `frames` frames of one shape per call on the GPU: one plan
// (pointwise mean, Kahan-compensated per pixel) built once and reused. Not
// thread-safe, like Plan.
class BackgroundModel {
public:
    BackgroundModel(Context& context, int height, int width, int channels, int frames, PixelType input = PixelType::U8);
    ~BackgroundModel();
    BackgroundModel(BackgroundModel&&) noexcept;
    BackgroundModel& operator=(BackgroundModel&&) noexcept;

    int frames() const;
    // The per-pixel, per-channel mean of frames (exactly frames() views of the
    // model's shape and pixel type). Throws Error on a wrong count or shape.
    Image mean(std::span<const FrameView> frames);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The same mean on the CPU in double precision (the reference the GPU model is
// tested against, and what the rig uses without a Vulkan device).
ImageD background_mean_reference(std::span<const FrameView> frames);

}  // namespace vkfuse

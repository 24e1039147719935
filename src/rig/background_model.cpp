// BackgroundModel: the mean of N frames as a Plan of the internal BackgroundMean kind.
#include "core/fusion_methods.hpp"
#include "core/validate_shape.hpp"
#include "rig/engine.hpp"
#include "vk/passes/graph.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/rig/background.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse {

struct BackgroundModel::Impl {
    Plan plan;
};

BackgroundModel::BackgroundModel(Context& context, int height, int width, int channels, int frames, PixelType input) {
    PlanConfig cfg;
    cfg.height = height;
    cfg.width = width;
    cfg.channels = channels;
    cfg.frames = frames;
    cfg.sensors = 1;
    cfg.input = input;
    cfg.want_fused = true;
    cfg.metrics = {};
    impl_ = std::make_unique<Impl>(Impl{vk::make_plan_of_kind(context, cfg, vk::PlanKind::BackgroundMean)});
}

BackgroundModel::~BackgroundModel() = default;
BackgroundModel::BackgroundModel(BackgroundModel&&) noexcept = default;
BackgroundModel& BackgroundModel::operator=(BackgroundModel&&) noexcept = default;

int BackgroundModel::frames() const { return impl_->plan.config().frames; }

Image BackgroundModel::mean(std::span<const FrameView> frames) {
    if (int(frames.size()) != this->frames())
        throw Error(ErrorKind::InvalidArgument, "background model: got " + std::to_string(frames.size()) +
                                                    " frames, built for " + std::to_string(this->frames()));
    impl_->plan.run(frames);
    return impl_->plan.fused(0);
}

ImageD background_mean_reference(std::span<const FrameView> frames) {
    if (frames.empty()) throw Error(ErrorKind::InvalidArgument, "background model: no frames");
    std::vector<ImageD> images;
    images.reserve(frames.size());
    for (const FrameView& v : frames) images.push_back(rig::to_double(v));
    core::validate_shape(images[0].height, images[0].width, images[0].channels, int(images.size()));
    core::check_frames(images);
    return core::fuse_mean(images);
}

}  // namespace vkfuse

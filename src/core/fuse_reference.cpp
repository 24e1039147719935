// fuse_reference(): validation, then dispatch to the method (include/vkfuse/reference.hpp).
#include <string>
#include <vector>

#include "core/check_finite.hpp"
#include "core/method_table.hpp"
#include "core/validate_shape.hpp"
#include "vkfuse/error.hpp"
#include "vkfuse/reference.hpp"

namespace vkfuse {
namespace {

std::string shape_text(const ImageD& f) {
    return std::to_string(f.height) + "x" + std::to_string(f.width) + "x" + std::to_string(f.channels);
}

}  // namespace

void core::check_frames(std::span<const ImageD> frames) {
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const std::string name = "frame " + std::to_string(k + 1);
        if (!frames[k].same_shape(frames[0]) || frames[k].data.size() != frames[0].pixels() * frames[0].channels)
            throw Error(ErrorKind::Shape, name + ": shape " + shape_text(frames[k]) + " differs from frame 1's " +
                                              shape_text(frames[0]));
        core::require_finite(frames[k], name);
    }
}

ImageD fuse_reference(std::span<const ImageD> frames, const FusionSpec& spec) {
    if (frames.empty()) validate(spec, 1, 1, 1, 0);  // throws the frame-count message
    validate(spec, frames[0].height, frames[0].width, frames[0].channels, int(frames.size()));
    core::check_frames(frames);
    return core::method_info(spec.method).reference(frames, spec);
}

}  // namespace vkfuse

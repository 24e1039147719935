// fuse_reference(): validation, then dispatch to the method (include/vkfuse/core/reference.hpp).
#include "core/method_table.hpp"
#include "core/validate_shape.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse {

ImageD fuse_reference(std::span<const ImageD> frames, const FusionSpec& spec) {
    if (frames.empty()) validate(spec, 1, 1, 1, 0);  // throws the frame-count message
    validate(spec, frames[0].height, frames[0].width, frames[0].channels, int(frames.size()));
    core::check_frames(frames);
    return core::method_info(spec.method).reference(frames, spec);
}

}  // namespace vkfuse

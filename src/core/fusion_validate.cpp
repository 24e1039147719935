// validate(): every precondition of a fusion, checked before any work, with a
// one-line message that names the offending option (include/vkfuse/core/fusion.hpp);
// and the shape and frame checks every plan and reference share
// (core/validate_shape.hpp).
#include <algorithm>
#include <string>

#include "core/check_finite.hpp"
#include "core/method_table.hpp"
#include "core/validate_shape.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse {
namespace {

[[noreturn]] void fail(const std::string& message) { throw Error(ErrorKind::InvalidArgument, message); }

std::string size_text(int height, int width) { return std::to_string(height) + "x" + std::to_string(width); }

std::string shape_text(const ImageD& f) { return size_text(f.height, f.width) + "x" + std::to_string(f.channels); }

// Side a square image needs for one level: dwt_max_level(n, F) >= 1 <=> n >= 2 (F - 1).
int min_side_for_one_level(Wavelet w) { return 2 * (filter_length(w) - 1); }

std::string why(const core::MethodInfo& m) { return m.limits_why.empty() ? "" : " (" + std::string(m.limits_why) + ")"; }

// K and C limits of the method's row (channel-sum: 3 frames of RGB).
void check_frame_count(const FusionSpec& spec, int channels, int frames) {
    const core::MethodInfo& m = core::method_info(spec.method);
    const std::string method = "--method " + std::string(m.name);
    if (m.exact_frames != 0 && frames != m.exact_frames)
        fail(method + ": needs exactly " + std::to_string(m.exact_frames) + " frames" + why(m) + ", got " +
             std::to_string(frames));
    if (m.exact_channels != 0 && channels != m.exact_channels)
        fail(method + ": needs " + std::to_string(m.exact_channels) + "-channel" +
             (m.exact_channels == 3 ? " (RGB)" : "") + " frames, got " + std::to_string(channels) + " channel(s)");
}

void check_wavelet_levels(const FusionSpec& spec, int height, int width) {
    const int levels = spec.effective_levels();
    const int most = max_wavelet_levels(spec.wavelet, height, width);
    const std::string wavelet(to_string(spec.wavelet));
    const std::string option =
        spec.levels == 0 ? "--levels (default " + std::to_string(levels) + ")" : "--levels " + std::to_string(levels);
    if (most == 0)
        fail(option + ": a " + size_text(height, width) + " image is too small for " + wavelet +
             " (one level needs both sides >= " + std::to_string(min_side_for_one_level(spec.wavelet)) + ")");
    if (levels > most)
        fail(option + ": a " + size_text(height, width) + " image carries at most " + std::to_string(most) +
             (most == 1 ? " level of " : " levels of ") + wavelet);
}

}  // namespace

int max_levels(Method method, Wavelet wavelet, int height, int width) {
    const core::MethodInfo& m = core::method_info(method);
    if (m.default_levels == 0) return 0;
    if (m.uses_wavelet) return max_wavelet_levels(wavelet, height, width);
    int levels = 1;  // pyrDown halves rounding up: the top is 1 x 1 after ceil(log2(max side)) levels
    for (int side = std::max(height, width); side > 2 && levels < m.max_levels; side = (side + 1) / 2) ++levels;
    return levels;
}

namespace core {

void validate_shape(int height, int width, int channels, int frames) {
    if (height < 1 || width < 1) fail("image size " + size_text(height, width) + ": both sides must be >= 1");
    if (channels != 1 && channels != 3)
        fail("image channels " + std::to_string(channels) + ": must be 1 (gray) or 3 (RGB)");
    if (frames < 1) fail("frames: need at least 1, got " + std::to_string(frames));
}

void check_frames(std::span<const ImageD> frames) {
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const std::string name = "frame " + std::to_string(k + 1);
        if (!frames[k].same_shape(frames[0]) || frames[k].data.size() != frames[0].pixels() * frames[0].channels)
            throw Error(ErrorKind::Shape, name + ": shape " + shape_text(frames[k]) + " differs from frame 1's " +
                                              shape_text(frames[0]));
        require_finite(frames[k], name);
    }
}

}  // namespace core

void validate(const FusionSpec& spec, int height, int width, int channels, int frames) {
    core::validate_shape(height, width, channels, frames);
    if (spec.levels < 0) fail("--levels " + std::to_string(spec.levels) + ": must be >= 0 (0 = method default)");
    check_frame_count(spec, channels, frames);
    const core::MethodInfo& m = core::method_info(spec.method);
    if (m.uses_wavelet) check_wavelet_levels(spec, height, width);
    // pyrDown of any size >= 1 is >= 1, so every Laplacian level count >= 1 is
    // computable; only the pointless ones past 1 x 1 are bounded (the row's max).
    if (m.max_levels != 0 && spec.effective_levels() > m.max_levels)
        fail("--levels " + std::to_string(spec.levels) + ": " + std::string(m.noun) + " takes at most " +
             std::to_string(m.max_levels) + " levels" + why(m));
}

}  // namespace vkfuse

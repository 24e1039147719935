// validate(): every precondition of a fusion, checked before any work, with a
// one-line message that names the offending option (include/vkfuse/fusion.hpp).
#include <string>

#include "core/validate_shape.hpp"
#include "vkfuse/error.hpp"
#include "vkfuse/fusion.hpp"

namespace vkfuse {
namespace {

[[noreturn]] void fail(const std::string& message) { throw Error(ErrorKind::InvalidArgument, message); }

std::string size_text(int height, int width) { return std::to_string(height) + "x" + std::to_string(width); }

// pyrDown halves each side (rounding up), so 31 levels take any image an int
// can size down to 1 x 1, and deeper levels only repeat that 1 x 1 top. The
// bound keeps an absurd --levels from allocating and recording one pyramid
// level per unit (2^31 levels ran out of memory instead of failing).
constexpr int kMaxLaplacianLevels = 32;

// Side a square image needs for one level: dwt_max_level(n, F) >= 1 <=> n >= 2 (F - 1).
int min_side_for_one_level(Wavelet w) { return 2 * (filter_length(w) - 1); }

void check_frame_count(const FusionSpec& spec, int channels, int frames) {
    const std::string method = "--method " + std::string(to_string(spec.method));
    if (spec.method == Method::ChannelSum) {
        if (frames != 3)
            fail(method + ": needs exactly 3 frames (red, green, blue LED), got " + std::to_string(frames));
        if (channels != 3)
            fail(method + ": needs 3-channel (RGB) frames, got " + std::to_string(channels) + " channel(s)");
    }
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

namespace core {

void validate_shape(int height, int width, int channels, int frames) {
    if (height < 1 || width < 1) fail("image size " + size_text(height, width) + ": both sides must be >= 1");
    if (channels != 1 && channels != 3)
        fail("image channels " + std::to_string(channels) + ": must be 1 (gray) or 3 (RGB)");
    if (frames < 1) fail("frames: need at least 1, got " + std::to_string(frames));
}

}  // namespace core

void validate(const FusionSpec& spec, int height, int width, int channels, int frames) {
    core::validate_shape(height, width, channels, frames);
    if (spec.levels < 0) fail("--levels " + std::to_string(spec.levels) + ": must be >= 0 (0 = method default)");
    check_frame_count(spec, channels, frames);
    if (spec.method == Method::Wavelet) check_wavelet_levels(spec, height, width);
    // pyrDown of any size >= 1 is >= 1, so every Laplacian level count >= 1 is
    // computable; only the pointless ones past 1 x 1 are bounded.
    if (spec.method == Method::Laplacian && spec.effective_levels() > kMaxLaplacianLevels)
        fail("--levels " + std::to_string(spec.levels) + ": a Laplacian pyramid takes at most " +
             std::to_string(kMaxLaplacianLevels) + " levels (31 reach 1x1 from any size)");
}

}  // namespace vkfuse

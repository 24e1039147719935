// vkfuse/core/fusion.hpp - what to fuse and how (docs/spec.md, "Fusion methods").
#pragma once
#include <string>
#include <string_view>

namespace vkfuse {

enum class Method {
    ChannelSum,   // K = 3, C = 3: R from frame 1, G from frame 2, B from frame 3
    Brovey,       // ratio-weighted sum across frames
    Laplacian,    // OpenCV-exact Laplacian pyramid, default 4 levels
    Wavelet,      // separable 2-D DWT, default 3 levels of bior4.4
};

enum class Wavelet { Haar, Db2, Bior22, Bior44 };
enum class WaveletMode {
    Periodization,  // exactly pywt.wavedec2/waverec2(mode="periodization")
    Symmetric,      // whole-sample symmetric lifting; perfect reconstruction at any size
};
enum class Rule { MaxAbs, Mean, Max, Min };

struct FusionSpec {
    Method method = Method::Wavelet;
    int levels = 0;  // 0: the method's default (laplacian 4, wavelet 3)
    Wavelet wavelet = Wavelet::Bior44;
    WaveletMode mode = WaveletMode::Periodization;
    Rule base_rule = Rule::Mean;       // approximation / top of pyramid
    Rule detail_rule = Rule::MaxAbs;   // every detail band / Laplacian level

    // The level count actually used (levels, or the method's default).
    int effective_levels() const;
};

// Names as the CLI spells them ("channel-sum", "bior4.4", "max-abs", ...).
// parse_* throw Error(InvalidArgument) naming the option and listing valid names.
std::string_view to_string(Method);
std::string_view to_string(Wavelet);
std::string_view to_string(WaveletMode);
std::string_view to_string(Rule);
Method parse_method(std::string_view);
Wavelet parse_wavelet(std::string_view);
WaveletMode parse_wavelet_mode(std::string_view);
Rule parse_rule(std::string_view);
// As parse_rule, naming the option in the message ("--base-rule" or "--detail-rule").
Rule parse_rule(std::string_view name, std::string_view option);
// The method with its wavelet where it has one: "wavelet/bior4.4", "laplacian"
// (how ROS 2's messages and the live page name a fusion).
std::string method_label(const FusionSpec& fusion);

// Length of PyWavelets' decomposition filter (haar 2, db2 4, bior2.2 6, bior4.4 10).
int filter_length(Wavelet);

// The deepest DWT a height x width image carries: pywt.dwt_max_level(min(h, w),
// filter_length), the same bound for both modes.
int max_wavelet_levels(Wavelet, int height, int width);

// The deepest level count validate() accepts for the method at this size
// (PyWavelets' level=None): max_wavelet_levels for a wavelet method, for a
// Laplacian pyramid the levels whose top first reaches 1 x 1 (at least 1),
// 0 for a method without levels.
int max_levels(Method, Wavelet, int height, int width);

// Checks spec against K frames of height x width x channels; throws
// Error(InvalidArgument) with a one-line reason (e.g. "--levels 5: a 61x97
// image carries at most 2 levels of bior4.4"). Returns nothing on success.
void validate(const FusionSpec&, int height, int width, int channels, int frames);

}  // namespace vkfuse

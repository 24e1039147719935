// core/method_table.hpp - one row per fusion method: what the library, the
// CLI, the bench and the tests know of a method apart from its arithmetic.
//
// method_info() switches over every Method with no default, so under -Wall
// -Werror a Method without its row does not compile; the Vulkan side has its
// own row per method (vk/plan/method_recorders.hpp), checked the same way. Names,
// parsing, default levels, validation, the reference dispatch, help text, the
// bench's axes, memory estimates and plot colours all read these rows.
#pragma once
#include <span>
#include <string>
#include <string_view>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::core {

struct MethodInfo {
    Method method;
    std::string_view name;     // as the CLI spells it
    std::string_view summary;  // one line of help
    std::string_view noun;     // in messages: "a Laplacian pyramid takes at most ..."
    int default_levels;        // 0: the method has no levels
    // The deepest level count accepted whatever the size (0: no levels); a
    // wavelet is further bounded by the size (max_wavelet_levels).
    int max_levels;
    int exact_frames;    // 0: any K >= 1
    int exact_channels;  // 0: 1 or 3
    // Why the limits above hold, for messages ("red, green, blue LED").
    std::string_view limits_why;
    bool uses_wavelet;   // the wavelet and mode apply
    // Frame k becomes channel k of the image: the study gives such a method a
    // combination's settings in the order that lights each channel best.
    bool frames_are_channels;
    // The double-precision reference (docs/spec.md), on frames fuse_reference
    // has validated: one shape, finite, K and C within the limits above.
    ImageD (*reference)(std::span<const ImageD> frames, const FusionSpec& spec);
    // Peak memory of the reference in images of one frame's size (double),
    // per frame and fixed: what the CLI checks before fusing on the CPU.
    double reference_images_per_frame, reference_images_fixed;
    std::string_view plot_colour;  // vkfuse-bench's SVG (wavelets: one per wavelet there)
    // Whether a fusion of this spec can be fused over a rectangle of changed
    // tiles alone (core/sparse_wavelet.hpp, the skip policy `tiles`); null:
    // never. The planner, its CPU twin and the plan all ask the row.
    bool (*tile_sparse)(const FusionSpec& spec);
};

// method_info(spec.method).tile_sparse, false where the row has none.
bool fuses_tile_sparse(const FusionSpec& spec);

const MethodInfo& method_info(Method m);
// Every row, in the order of the Method enumerators.
std::span<const MethodInfo> method_table();
// "channel-sum, brovey, laplacian or wavelet": the names for help text.
std::string method_names(std::string_view last_separator = " or ");
// Help text with "{methods}" (if present) replaced by method_names(last_separator),
// so a method's row is the only place that lists it.
std::string with_method_names(std::string_view help, std::string_view last_separator = " or ");

}  // namespace vkfuse::core

#include "fusion_options.hpp"

namespace vkfuse::cli {

FusionSpec fusion_options(const Args& args, FusionSpec spec) {
    if (auto v = args.value("--levels")) spec.levels = parse_positive_int("--levels", *v);
    if (auto v = args.value("--wavelet")) spec.wavelet = parse_wavelet(*v);
    if (auto v = args.value("--mode")) spec.mode = parse_wavelet_mode(*v);
    if (auto v = args.value("--base-rule")) spec.base_rule = parse_rule(*v, "--base-rule");
    if (auto v = args.value("--detail-rule")) spec.detail_rule = parse_rule(*v, "--detail-rule");
    return spec;
}

}  // namespace vkfuse::cli

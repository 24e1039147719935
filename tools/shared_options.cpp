#include "shared_options.hpp"

#include <cstdio>

#include "vkfuse/core/error.hpp"
#include "vkfuse/study/study.hpp"

namespace vkfuse::cli {

Backend parse_backend_option(std::string_view text) {
    if (const std::optional<Backend> b = parse_backend(text)) return *b;
    throw Error(ErrorKind::InvalidArgument, "--backend " + std::string(text) + ": expected cpu, vulkan or auto");
}

std::optional<Context> open_backend(Backend choice) {
    std::string why;
    std::optional<Context> context = vkfuse::open_backend(choice, "--backend", &why);
    if (!context && choice == Backend::Auto)
        std::fprintf(stderr, "vkfuse: no usable Vulkan device (%s); using the CPU reference path\n", why.c_str());
    return context;
}

FusionSpec fusion_options(const Args& args, FusionSpec spec) {
    if (auto v = args.value("--levels")) spec.levels = parse_positive_int("--levels", *v);
    if (auto v = args.value("--wavelet")) spec.wavelet = parse_wavelet(*v);
    if (auto v = args.value("--mode")) spec.mode = parse_wavelet_mode(*v);
    if (auto v = args.value("--base-rule")) spec.base_rule = parse_rule(*v, "--base-rule");
    if (auto v = args.value("--detail-rule")) spec.detail_rule = parse_rule(*v, "--detail-rule");
    return spec;
}

std::vector<std::string> parse_study_methods(const Args& args) {
    const auto text = args.value("--methods");
    if (!text) return {};
    std::vector<std::string> names = split_list(*text);
    select_study_methods(names, "--methods");
    return names;
}

}  // namespace vkfuse::cli

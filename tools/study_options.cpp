#include "study_options.hpp"

#include "vkfuse/study/study.hpp"

namespace vkfuse::cli {

std::vector<std::string> parse_study_methods(const Args& args) {
    const auto text = args.value("--methods");
    if (!text) return {};
    std::vector<std::string> names = split_list(*text);
    select_study_methods(names, "--methods");
    return names;
}

}  // namespace vkfuse::cli

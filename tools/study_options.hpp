// study_options.hpp - what `vkfuse study` and `vkfuse tune` both take about
// the study itself.
#pragma once
#include <string>
#include <vector>

#include "args.hpp"

namespace vkfuse::cli {

// The --methods option, the same for both commands.
inline constexpr OptionSpec kStudyMethodsOption{
    "--methods", "", "A,B",
    "methods studied, each {methods} (every wavelet family) or one family as wavelet-bior4.4 (default all)"};

// --methods as StudyOptions::methods takes it (empty when not given), checked
// now: a bad name fails before anything is read or captured.
std::vector<std::string> parse_study_methods(const Args& args);

}  // namespace vkfuse::cli

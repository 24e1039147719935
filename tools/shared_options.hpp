// shared_options.hpp - the options more than one command takes, declared
// once: --backend (every command that computes), the fusion spec (`vkfuse fuse`,
// `vkfuse run`) and --methods (`vkfuse study`, `vkfuse tune`).
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "args.hpp"
#include "vkfuse/core/fusion.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::cli {

// The --backend option, the same for every command that computes.
inline constexpr OptionSpec kBackendOption{
    "--backend", "", "B", "cpu, vulkan or auto (default auto: Vulkan when a usable device exists, else cpu)"};

// "cpu", "vulkan" or "auto"; throws Error(InvalidArgument) naming --backend otherwise.
Backend parse_backend_option(std::string_view text);

// vkfuse::open_backend for a command: Auto's fallback to the CPU is said in
// one line on stderr; Vulkan without a device throws naming --backend.
std::optional<Context> open_backend(Backend choice);

inline constexpr OptionSpec kLevelsOption{"--levels", "", "L",
                                          "pyramid or DWT levels (default: laplacian 4, wavelet 3)"};
inline constexpr OptionSpec kWaveletOption{"--wavelet", "", "W", "haar, db2, bior2.2 or bior4.4 (default bior4.4)"};
inline constexpr OptionSpec kModeOption{"--mode", "", "MODE",
                                        "DWT border: periodization or symmetric (default periodization)"};
inline constexpr OptionSpec kBaseRuleOption{
    "--base-rule", "", "R", "rule for the approximation / pyramid top: max-abs, mean, max, min (default mean)"};
inline constexpr OptionSpec kDetailRuleOption{"--detail-rule", "", "R",
                                              "rule for detail bands / Laplacian levels (default max-abs)"};

// base with --levels, --wavelet, --mode, --base-rule and --detail-rule
// applied; each bad value throws Error(InvalidArgument) naming its option.
FusionSpec fusion_options(const Args& args, FusionSpec base);

// The --methods option of the study and its tuning.
inline constexpr OptionSpec kStudyMethodsOption{
    "--methods", "", "A,B",
    "methods studied, each {methods} (every wavelet family) or one family as wavelet-bior4.4 (default all)"};

// --methods as StudyOptions::methods takes it (empty when not given), checked
// now: a bad name fails before anything is read or captured.
std::vector<std::string> parse_study_methods(const Args& args);

}  // namespace vkfuse::cli

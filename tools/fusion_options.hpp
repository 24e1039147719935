// fusion_options.hpp - the fusion options `vkfuse fuse` and `vkfuse run` share.
#pragma once
#include "args.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse::cli {

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

}  // namespace vkfuse::cli

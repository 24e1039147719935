// run_config.hpp - the file `vkfuse tune` writes and `vkfuse run --config`
// reads: an LED sequence and how to fuse it.
//
//   {"format": "vkfuse-config", "version": 1,
//    "sequence": "15,15,15+0,15,0", "method": "wavelet", "wavelet": "bior4.4",
//    "levels": 0, "mode": "periodization", "base_rule": "mean",
//    "detail_rule": "max-abs", "tuned": {...what the study found...}}
//
// Every member but format, version and sequence is optional (the defaults
// of `vkfuse run`); "tuned" is for people and is not read.
#pragma once
#include <string>

#include "io/json_value.hpp"
#include "vkfuse/core/fusion.hpp"
#include "vkfuse/sensor/illumination.hpp"

namespace vkfuse::cli {

struct RunConfig {
    IlluminationSequence sequence;
    FusionSpec fusion;
};

// The file's text for config, with `tuned` (null: left out).
std::string run_config_json(const RunConfig& config, json::Value tuned);

// Reads and checks path (at most 1 MiB, read by io::read_file_bytes).
// Throws Error "--config <path>: <problem>": InvalidArgument for anything
// malformed, Format for a file over the limit, Io when it cannot be read.
RunConfig read_run_config(const std::string& path);

}  // namespace vkfuse::cli

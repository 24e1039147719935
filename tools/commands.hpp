// commands.hpp - the subcommands of `vkfuse`: how each is described and run.
#pragma once
#include "args.hpp"

namespace vkfuse::cli {

// A subcommand: its description (options, --help) and its body, which returns
// the exit status and reports failures by throwing vkfuse::Error.
struct Command {
    const CommandSpec& spec;
    int (*run)(const Args&);
};

extern const Command fuse_command;
extern const Command metrics_command;
extern const Command info_command;
extern const Command run_command;
extern const Command sim_command;
extern const Command convert_command;
extern const Command study_command;
extern const Command tune_command;
extern const Command devices_command;

}  // namespace vkfuse::cli

// vkfuse: the command line. Dispatches to a subcommand and turns every failure
// into one line on stderr and exit status 2.
#include <algorithm>
#include <array>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vkfuse/vk/context.hpp"
#include "standard_output.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/version.hpp"

namespace vkfuse::cli {
namespace {

constexpr int kFailure = 2;

const std::array<const Command*, 9> kCommands{&fuse_command,  &metrics_command, &run_command,
                                               &sim_command,   &convert_command, &study_command,
                                               &tune_command,  &info_command,    &devices_command};

std::string top_level_help() {
    std::string text = "vkfuse " + std::string(kVersion) +
                       " - fuse multi-illumination tactile sensor frames and score them\n\n"
                       "Usage: vkfuse <command> [options]\n"
                       "       vkfuse --help | --version\n\nCommands:\n";
    for (const Command* c : kCommands) {
        std::string name(c->spec.name);
        text += "  " + name + std::string(10 - name.size(), ' ') + std::string(c->spec.summary) + "\n";
    }
    return text +
           "\nRun 'vkfuse <command> --help' for its options.\n"
           "Exit status: 0 on success, 2 on bad input or usage (one line on stderr).\n\n"
           "Example:\n  vkfuse fuse --method brovey -o fused.png frame1.png frame2.png\n";
}

const Command* find_command(const std::string& name) {
    auto it = std::find_if(kCommands.begin(), kCommands.end(), [&](const Command* c) { return c->spec.name == name; });
    return it == kCommands.end() ? nullptr : *it;
}

int dispatch(const std::vector<std::string>& argv) {
    if (argv.empty()) throw Error(ErrorKind::InvalidArgument, "missing command (see 'vkfuse --help')");
    const std::string& first = argv.front();
    if (first == "-h" || first == "--help") {
        std::fputs(top_level_help().c_str(), stdout);
        return 0;
    }
    if (first == "--version") {
        std::printf("vkfuse %s\n", std::string(kVersion).c_str());
        return 0;
    }
    const Command* command = find_command(first);
    if (!command) throw Error(ErrorKind::InvalidArgument, "unknown command '" + first + "' (see 'vkfuse --help')");
    std::span<const std::string> rest(argv.begin() + 1, argv.end());
    if (wants_help(rest)) {
        std::fputs(help_text(command->spec).c_str(), stdout);
        return 0;
    }
    const Args args = Args::parse(command->spec, rest);
    check_vulkan_environment();  // a bad VKFUSE_DEVICE_PROFILE fails before any output
    return command->run(args);
}

// The message on one line, however it was written.
int report(std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::fprintf(stderr, "vkfuse: %s\n", message.c_str());
    return kFailure;
}

}  // namespace
}  // namespace vkfuse::cli

int main(int argc, char** argv) {
    using namespace vkfuse::cli;
    try {
        return checked_stdout(dispatch(std::vector<std::string>(argv + 1, argv + argc)));
    } catch (const std::bad_alloc&) {
        return report("out of memory");
    } catch (const std::exception& e) {
        return report(e.what());
    } catch (...) {
        return report("internal error: an unknown exception");  // still one line and exit 2, never an abort
    }
}

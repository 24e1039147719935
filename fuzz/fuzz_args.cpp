// The command line parser on arbitrary argv: NUL-separated words, the first
// naming the command as in `vkfuse <command> ...`. Args::parse runs with the
// real command descriptions, then everything each command reads from its
// options before it touches a file (fusion options, backend, output format,
// run options). The outcome is options or an Error(InvalidArgument) with a
// message; never a crash, undefined behaviour or a leak.
#include <span>
#include <string>
#include <vector>

#include "commands.hpp"
#include "fuzz_targets.hpp"
#include "run/run_options.hpp"
#include "shared_options.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::fuzz {
namespace {

std::vector<std::string> split_words(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> words;
    std::string word;
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == 0) {
            words.push_back(word);
            word.clear();
        } else {
            word += char(data[i]);
        }
    }
    if (!word.empty()) words.push_back(word);
    return words;
}

const cli::Command* find_command(const std::string& name) {
    for (const cli::Command* c : {&cli::fuse_command, &cli::metrics_command, &cli::info_command, &cli::run_command,
                                  &cli::sim_command, &cli::study_command, &cli::tune_command})
        if (c->spec.name == name) return c;
    return nullptr;
}

// What each command derives from its options before any file I/O.
void read_options(const cli::Command& command, const cli::Args& args) {
    for (const cli::OptionSpec& o : command.spec.options) (void)args.value(o.name);
    const std::string_view name = command.spec.name;
    if (name == "fuse") {
        FusionSpec spec;
        spec.method = parse_method(args.required("--method"));
        (void)cli::fusion_options(args, spec);
        (void)cli::parse_backend_option(args.value("--backend").value_or("auto"));
        io::check_image_extension(args.required("-o"));
    } else if (name == "metrics") {
        (void)cli::parse_backend_option(args.value("--backend").value_or("auto"));
    } else if (name == "run") {
        (void)cli::parse_run_options(args);
    }
}

}  // namespace

int args(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::string> argv = split_words(data, size);
    if (argv.empty()) return 0;
    const cli::Command* command = find_command(argv.front());
    if (!command) return 0;
    const std::span<const std::string> rest(argv.begin() + 1, argv.end());
    try {
        if (cli::wants_help(rest)) {
            if (cli::help_text(command->spec).empty()) violated("help", "empty help text");
            return 0;
        }
        read_options(*command, cli::Args::parse(command->spec, rest));
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::InvalidArgument) violated("error kind", e.what());
        if (std::string(e.what()).empty()) violated("error message", "empty");
    }
    return 0;
}

}  // namespace vkfuse::fuzz

VKFUSE_FUZZ_ENTRY(vkfuse::fuzz::args)

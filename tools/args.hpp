// args.hpp - the small option parser every vkfuse subcommand shares.
#pragma once
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vkfuse::cli {

// One option of a subcommand: it takes exactly one value, or none when value
// is empty (a flag such as --virtual-clock).
struct OptionSpec {
    std::string_view name;   // "--levels", or "-o"
    std::string_view alias;  // "--output", or empty
    std::string_view value;  // how help names the value: "L"; empty for a flag
    std::string_view help;   // one line, saying the default

    bool is_flag() const { return value.empty(); }
};

// What a subcommand accepts and how --help describes it.
struct CommandSpec {
    std::string_view name;      // "fuse"
    std::string_view summary;   // one line for `vkfuse --help`
    std::string_view usage;     // "vkfuse fuse --method M [options] -o OUT IN..."
    std::string_view details;   // a paragraph after the usage line
    std::span<const OptionSpec> options;
    std::string_view example;
};

// Options (by their canonical name) and operands of one command line.
// Options and operands may be mixed; "--" ends the options; the last
// occurrence of an option wins; "--name=value" is accepted.
class Args {
public:
    // Throws Error(InvalidArgument) "<command>: unknown option --x (see 'vkfuse <command> --help')".
    static Args parse(const CommandSpec& spec, std::span<const std::string> argv);

    std::optional<std::string> value(std::string_view name) const;
    // Every value of an option given more than once, in order (for
    // repeatable options such as `run --sensor`).
    std::vector<std::string> values(std::string_view name) const;
    // Whether a flag (or any option) was given.
    bool has(std::string_view name) const { return value(name).has_value(); }
    // The value of a required option; throws "<command>: missing -o OUT (see ...)" when absent.
    std::string required(std::string_view name) const;
    const std::vector<std::string>& operands() const { return operands_; }
    // Throws Error(InvalidArgument) "<command>: <problem> (see 'vkfuse <command> --help')".
    [[noreturn]] void usage_error(const std::string& problem) const;

private:
    explicit Args(const CommandSpec& spec) : spec_(&spec) {}

    const CommandSpec* spec_;
    std::map<std::string, std::vector<std::string>, std::less<>> values_;
    std::vector<std::string> operands_;
};

// True when argv asks for help (-h or --help before any "--").
bool wants_help(std::span<const std::string> argv);

// The --help text of a subcommand: usage, details, options, example.
std::string help_text(const CommandSpec& spec);
// One option's help line, "{methods}" replaced by the method names.
std::string option_help(const OptionSpec& option);

// "a,b,c" -> {"a", "b", "c"}: the value of a list option (empty items kept,
// for the caller to refuse by name).
std::vector<std::string> split_list(const std::string& text);

// A positive decimal int; throws Error(InvalidArgument) "--levels abc: expected a positive integer".
int parse_positive_int(std::string_view option, const std::string& text);
// A decimal int >= 0; throws Error(InvalidArgument) "--frames x: expected a non-negative integer".
int parse_count(std::string_view option, const std::string& text);
// A finite decimal number > 0; throws Error(InvalidArgument) "--skip-threshold x: expected a positive number".
double parse_positive_number(std::string_view option, const std::string& text, std::string_view unit = "");
// The same, "--duration x: expected a positive number of seconds".
inline double parse_seconds(std::string_view option, const std::string& text) {
    return parse_positive_number(option, text, " of seconds");
}

}  // namespace vkfuse::cli

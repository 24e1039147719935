#include "args.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "core/method_table.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {
namespace {

const OptionSpec* find_option(const CommandSpec& spec, std::string_view name) {
    auto it = std::find_if(spec.options.begin(), spec.options.end(),
                           [&](const OptionSpec& o) { return o.name == name || (!o.alias.empty() && o.alias == name); });
    return it == spec.options.end() ? nullptr : &*it;
}

bool is_option(const std::string& arg) { return arg.size() > 1 && arg[0] == '-'; }

}  // namespace

Args Args::parse(const CommandSpec& spec, std::span<const std::string> argv) {
    Args args(spec);
    bool options_ended = false;
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& arg = argv[i];
        if (options_ended || !is_option(arg)) {
            args.operands_.push_back(arg);
            continue;
        }
        if (arg == "--") {
            options_ended = true;
            continue;
        }
        std::size_t eq = arg.starts_with("--") ? arg.find('=') : std::string::npos;
        std::string name = arg.substr(0, eq);
        const OptionSpec* option = find_option(spec, name);
        if (!option) args.usage_error("unknown option " + name);
        if (option->is_flag()) {
            if (eq != std::string::npos) args.usage_error("option " + name + " takes no value");
            args.values_[std::string(option->name)].push_back("");
            continue;
        }
        if (eq == std::string::npos && i + 1 == argv.size())
            args.usage_error("option " + name + " needs a value " + std::string(option->value));
        args.values_[std::string(option->name)].push_back(eq == std::string::npos ? argv[++i] : arg.substr(eq + 1));
    }
    return args;
}

std::optional<std::string> Args::value(std::string_view name) const {
    auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second.back();
}

std::vector<std::string> Args::values(std::string_view name) const {
    auto it = values_.find(name);
    return it == values_.end() ? std::vector<std::string>{} : it->second;
}

std::string Args::required(std::string_view name) const {
    auto v = value(name);
    if (!v) usage_error("missing " + std::string(name) + " " + std::string(find_option(*spec_, name)->value));
    return *v;
}

void Args::usage_error(const std::string& problem) const {
    std::string command(spec_->name);
    throw Error(ErrorKind::InvalidArgument, command + ": " + problem + " (see 'vkfuse " + command + " --help')");
}

bool wants_help(std::span<const std::string> argv) {
    for (const std::string& arg : argv) {
        if (arg == "--") return false;
        if (arg == "-h" || arg == "--help") return true;
    }
    return false;
}

std::string option_help(const OptionSpec& option) { return core::with_method_names(option.help); }

std::string help_text(const CommandSpec& spec) {
    std::string text = "Usage: " + std::string(spec.usage) + "\n\n" + std::string(spec.details) + "\n\nOptions:\n";
    auto label = [](const OptionSpec& o) {
        return (o.alias.empty() ? std::string(o.name) : std::string(o.name) + ", " + std::string(o.alias)) +
               (o.is_flag() ? "" : " " + std::string(o.value));
    };
    std::size_t width = std::string_view("-h, --help").size();
    for (const OptionSpec& o : spec.options) width = std::max(width, label(o).size());
    auto line = [&](const std::string& left, std::string_view help) {
        return "  " + left + std::string(width - left.size() + 2, ' ') + std::string(help) + "\n";
    };
    bool names_methods = false;
    for (const OptionSpec& o : spec.options) {
        text += line(label(o), option_help(o));
        names_methods = names_methods || o.help.find("{methods}") != std::string_view::npos;
    }
    text += line("-h, --help", "show this help and exit");
    if (names_methods) {  // a command that takes a method says what each one does
        text += "\nMethods:\n";
        std::size_t name_width = 0;
        for (const core::MethodInfo& m : core::method_table()) name_width = std::max(name_width, m.name.size());
        for (const core::MethodInfo& m : core::method_table())
            text += "  " + std::string(m.name) + std::string(name_width - m.name.size() + 2, ' ') +
                    std::string(m.summary) + "\n";
    }
    return text + "\nExample:\n  " + std::string(spec.example) + "\n";
}

int parse_positive_int(std::string_view option, const std::string& text) {
    int value = 0;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || value < 1)
        throw Error(ErrorKind::InvalidArgument,
                    std::string(option) + " " + text + ": expected a positive integer");
    return value;
}

int parse_count(std::string_view option, const std::string& text) {
    int value = 0;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || value < 0)
        throw Error(ErrorKind::InvalidArgument, std::string(option) + " " + text + ": expected a non-negative integer");
    return value;
}

double parse_positive_number(std::string_view option, const std::string& text, std::string_view unit) {
    double value = 0;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value) || value <= 0)
        throw Error(ErrorKind::InvalidArgument,
                    std::string(option) + " " + text + ": expected a positive number" + std::string(unit));
    return value;
}

std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(',', start);
        parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
        if (end == std::string::npos) return parts;
        start = end + 1;
    }
}

}  // namespace vkfuse::cli

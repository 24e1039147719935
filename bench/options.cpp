#include "options.hpp"

#include <charconv>
#include <functional>
#include <map>

#include "vkfuse/core/error.hpp"

namespace vkfuse::bench {
namespace {

std::vector<std::string_view> split_commas(std::string_view option, std::string_view text) {
    std::vector<std::string_view> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        std::string_view item = text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
        if (item.empty()) throw UsageError(std::string(option) + ": empty item in \"" + std::string(text) + "\"");
        out.push_back(item);
        if (comma == std::string_view::npos) return out;
        start = comma + 1;
    }
}

int parse_int(std::string_view option, std::string_view text, int lo, int hi) {
    int v = 0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size() || v < lo || v > hi)
        throw UsageError(std::string(option) + ": expected an integer in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "], got \"" + std::string(text) + "\"");
    return v;
}

double parse_positive(std::string_view option, std::string_view text) {
    double v = 0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size() || !(v > 0))
        throw UsageError(std::string(option) + ": expected a positive number, got \"" + std::string(text) + "\"");
    return v;
}

// The library's name parsers throw vkfuse::Error naming the option and the
// valid names; on the command line that is a usage error.
template <class F>
auto library_name(F parse, std::string_view text) {
    try {
        return parse(text);
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
}

template <class T, class F>
void add_list(std::vector<T>& out, std::string_view option, std::string_view text, F parse_one) {
    for (auto item : split_commas(option, text)) out.push_back(parse_one(item));
}

using Setter = std::function<void(Options&, std::string_view option, std::string_view value)>;

const std::map<std::string, Setter, std::less<>>& setters() {
    static const std::map<std::string, Setter, std::less<>> table{
        {"--method", [](Options& o, auto opt, auto v) {
             add_list(o.methods, opt, v, [](auto s) { return library_name([](auto t) { return parse_method(t); }, s); });
         }},
        {"--wavelet", [](Options& o, auto opt, auto v) {
             add_list(o.wavelets, opt, v, [](auto s) { return library_name([](auto t) { return parse_wavelet(t); }, s); });
         }},
        {"--backend", [](Options& o, auto opt, auto v) {
             add_list(o.backends, opt, v, [&](auto s) { return parse_backend(opt, s); });
         }},
        {"--precision", [](Options& o, auto opt, auto v) {
             add_list(o.precisions, opt, v, [&](auto s) { return parse_precision(opt, s); });
         }},
        {"--size", [](Options& o, auto opt, auto v) { add_list(o.sizes, opt, v, [&](auto s) { return parse_size(opt, s); }); }},
        {"--frames", [](Options& o, auto opt, auto v) {
             add_list(o.frames, opt, v, [&](auto s) { return parse_int(opt, s, 2, 16); });
         }},
        {"--sensors", [](Options& o, auto opt, auto v) {
             add_list(o.sensors, opt, v, [&](auto s) { return parse_int(opt, s, 1, 4096); });
         }},
        {"--levels", [](Options& o, auto opt, auto v) {
             add_list(o.levels, opt, v, [&](auto s) { return parse_int(opt, s, 1, 16); });
         }},
        {"--json", [](Options& o, auto, auto v) { o.json_path = std::string(v); }},
        {"--python", [](Options& o, auto, auto v) { o.python = std::string(v); }},
        {"--plot", [](Options& o, auto, auto v) { o.plot_path = std::string(v); }},
        {"--runs", [](Options& o, auto opt, auto v) { o.runs = parse_int(opt, v, 1, 100000); }},
        {"--warmup", [](Options& o, auto opt, auto v) { o.warmup = parse_int(opt, v, 0, 1000); }},
        {"--cell-seconds", [](Options& o, auto opt, auto v) { o.cell_seconds = parse_positive(opt, v); }},
        {"--device", [](Options& o, auto opt, auto v) { o.device = parse_int(opt, v, 0, 64); }},
        {"--mem-limit", [](Options& o, auto opt, auto v) { o.mem_limit_gib = parse_positive(opt, v); }},
    };
    return table;
}

const std::map<std::string, std::function<void(Options&)>, std::less<>>& flags() {
    static const std::map<std::string, std::function<void(Options&)>, std::less<>> table{
        {"--quick", [](Options& o) { o.scope = Scope::Quick; }},
        {"--full", [](Options& o) { o.scope = Scope::Full; }},
        {"--profile", [](Options& o) { o.profile = true; }},
        {"--no-peers", [](Options& o) { o.peers = false; }},
        {"--list", [](Options& o) { o.list = true; }},
        {"--probe", [](Options& o) { o.probe = true; }},
        {"--scenes", [](Options& o) { o.scenes = true; }},
        {"--windows", [](Options& o) { o.windows = true; }},
        {"--pipeline", [](Options& o) { o.pipeline = true; }},
        {"--help", [](Options& o) { o.help = true; }},
        {"-h", [](Options& o) { o.help = true; }},
    };
    return table;
}

void check_output_name(std::string_view option, const std::string& path, std::string_view extension) {
    if (path.empty()) throw UsageError(std::string(option) + ": empty file name");
    if (path.size() < extension.size() || path.compare(path.size() - extension.size(), extension.size(), extension) != 0)
        throw UsageError(std::string(option) + " " + path + ": expected a file name ending in " + std::string(extension));
}

}  // namespace

Options parse_options(const std::vector<std::string>& args) {
    Options o;
    bool quick = false, full = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string_view arg = args[i];
        if (auto f = flags().find(arg); f != flags().end()) {
            f->second(o);
            quick |= arg == "--quick";
            full |= arg == "--full";
            continue;
        }
        const std::size_t eq = arg.find('=');
        const std::string_view name = arg.substr(0, eq);
        auto s = setters().find(name);
        if (s == setters().end()) throw UsageError(std::string(arg) + ": unknown option (see --help)");
        std::string_view value;
        if (eq != std::string_view::npos) {
            value = arg.substr(eq + 1);
        } else if (i + 1 < args.size()) {
            value = args[++i];
        } else {
            throw UsageError(std::string(name) + ": missing value");
        }
        s->second(o, name, value);
    }
    if (quick && full) throw UsageError("--quick and --full: choose one");
    if (!o.json_path.empty()) check_output_name("--json", o.json_path, ".json");
    if (!o.plot_path.empty()) check_output_name("--plot", o.plot_path, ".svg");
    return o;
}

}  // namespace vkfuse::bench

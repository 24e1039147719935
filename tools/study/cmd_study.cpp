// vkfuse study: the paper's search for the best LED settings and fusion
// method, on a dataset of the user's own sensor (vkfuse/study/study.hpp).
#include <chrono>
#include <cstdio>
#include <string>

#include "shared_options.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "staged_directory.hpp"
#include "standard_output.hpp"
#include "stop_signal.hpp"
#include "study/study_output.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/dataset.hpp"
#include "vkfuse/study/study.hpp"

namespace vkfuse::cli {
namespace {

constexpr OptionSpec kOptions[] = {
    {"--out", "", "DIR", "where results.json, report.md and the plots go, created new (default study)"},
    {"--max-k", "", "N", "combinations of 1..N settings (default 5)"},
    {"--quick", "", "", "a first look: combinations of up to 3 settings, the first two objects"},
    {"--objects", "", "A,B", "objects to study (default every object of the dataset)"},
    kStudyMethodsOption,
    {"--sensor", "", "SERIAL", "the dataset's sensor to study (default its first)"},
    {"--greedy-max", "", "N", "greedy sequences up to N settings (default 12)"},
    {"--top", "", "N", "best pairs kept per metric (default 10)"},
    kBackendOption,
};

constexpr CommandSpec kSpec{
    "study",
    "score every combination of a dataset's LED settings with every fusion method (or --methods), as the paper did",
    "vkfuse study DATASET [--out DIR] [--max-k N | --quick] [--objects A,B] [--methods A,B] [--backend B]",
    "DATASET holds, per object, a frame under each LED setting and a background\n"
    "(nothing pressed) under each: `vkfuse sim`, or `vkfuse sim`'s layout recorded\n"
    "from a real DIGIT (README, \"Studying your sensor\"). Every combination of 1..N\n"
    "settings is fused by every method (or those of --methods) and scored\n"
    "(sharpness, RMS contrast, difference with background) against the static\n"
    "setting's frame; then the paper's analysis: methods, best pairs, greedy\n"
    "sequences, pairings. Writes results.json, report.md and SVG plots.",
    kOptions,
    "vkfuse study coin-set --quick --out coin-study",
};

std::string eta(double seconds) {
    const long s = long(seconds + 0.5);
    char text[32];
    std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
    return text;
}

// "1 method", "7 methods".
std::string counted(std::size_t n, const std::string& noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

int run(const Args& args) {
    if (args.operands().size() != 1)
        args.usage_error(args.operands().empty() ? "missing DATASET" : "one DATASET at a time");
    const std::string dataset_dir = args.operands().front();
    StudyOptions options;
    const bool quick = args.has("--quick");
    if (quick && args.has("--max-k")) args.usage_error("--quick and --max-k both choose the combinations");
    options.max_k = quick ? 3 : args.has("--max-k") ? parse_positive_int("--max-k", *args.value("--max-k")) : 5;
    if (options.max_k < 2) args.usage_error("--max-k 1: a study fuses combinations of at least 2 settings");
    if (auto v = args.value("--objects")) options.objects = split_list(*v);
    options.methods = parse_study_methods(args);
    if (auto v = args.value("--sensor")) options.serial = *v;
    if (auto v = args.value("--greedy-max")) options.greedy_max = parse_positive_int("--greedy-max", *v);
    if (auto v = args.value("--top")) options.top = parse_positive_int("--top", *v);
    const Backend backend = parse_backend_option(args.value("--backend").value_or("auto"));
    const std::string out = args.value("--out").value_or("study");

    const Dataset dataset = read_dataset(dataset_dir);
    if (!dataset.incomplete.empty()) std::fprintf(stderr, "vkfuse study: %s\n", dataset.incomplete.c_str());
    if (quick && options.objects.empty()) {
        options.objects = dataset.objects();
        if (options.objects.size() > 2) options.objects.resize(2);
    }
    StopSignal stop;
    StagedDirectory staged(out, StagedDirectory::Policy{"--out", false, nullptr, ""});
    std::optional<Context> context = open_backend(backend);
    Progress progress("vkfuse study");
    const auto start = std::chrono::steady_clock::now();
    options.progress = [&](std::size_t done, std::size_t total) {
        if (stop.requested()) throw Error(ErrorKind::InvalidArgument, "--out " + out + ": interrupted; nothing written");
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double left = done > 0 ? elapsed * double(total - done) / double(done) : 0;
        progress.status(std::to_string(done) + " / " + std::to_string(total) + " method x combination steps, " + eta(elapsed) +
                        " elapsed, about " + eta(left) + " left");
    };
    const StudyResult result = run_study(dataset, options, context ? &*context : nullptr);
    progress.finish();
    write_study(staged.path(), dataset_dir, result);
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.1f", result.seconds);
    // Reported before it is published: a report that cannot be delivered
    // fails the command with nothing published.
    print_checked(dataset_dir + ": " + std::to_string(result.combinations) + " combinations x " +
                  counted(result.methods.size(), "method") + " on " + counted(result.objects.size(), "object") +
                  " in " + seconds + " s; most likely to improve every metric: " + result.best_method +
                  "; report in " + out + "/report.md\n");
    staged.publish();
    return 0;
}

}  // namespace

const Command study_command{kSpec, run};

}  // namespace vkfuse::cli

// vkfuse tune: the study on the user's own sensor, captured now (or a
// dataset), and its winner written as a configuration `vkfuse run --config`
// takes.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "shared_options.hpp"
#include "commands.hpp"
#include "io/atomic_write.hpp"
#include "io/path_component.hpp"
#include "progress.hpp"
#include "run/run_config.hpp"
#include "run/run_sensors.hpp"
#include "sim_record.hpp"
#include "staged_directory.hpp"
#include "standard_output.hpp"
#include "stop_signal.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/study/study.hpp"

namespace vkfuse::cli {
namespace {

constexpr OptionSpec kOptions[] = {
    {"--out", "", "FILE", "the configuration written (default vkfuse-config.json)"},
    {"--dataset", "", "DIR", "study this dataset instead of capturing (vkfuse sim, or one recorded before)"},
    {"--sensor", "", "SERIAL", "the DIGIT to capture from (default the one plugged in, else the simulated DIGIT)"},
    {"--simulate", "", "", "capture from the simulated DIGIT even when a DIGIT is plugged in"},
    {"--objects", "", "A,B", "what is pressed, one after another (simulated default coin,lego; a DIGIT needs them named)"},
    {"--grid", "", "V,V", "LED levels 0..15; every r,g,b combination is captured (default 0,15: 8 settings)"},
    {"--background-frames", "", "N", "no-contact frames averaged per setting (default 4)"},
    {"--max-k", "", "N", "combinations of 1..N settings (default 3)"},
    kStudyMethodsOption,
    {"--keep", "", "DIR", "also keep the captured frames as a dataset (a new directory) for vkfuse study or run --replay"},
    kBackendOption,
};

constexpr CommandSpec kSpec{
    "tune",
    "find the LED sequence and fusion method that serve your sensor best, as a config for vkfuse run",
    "vkfuse tune [--out FILE] [--dataset DIR | --sensor SERIAL | --simulate] [--objects A,B] [--grid V,V] [--methods A,B]",
    "Captures, on the DIGIT plugged in (asking you on the terminal to press each\n"
    "object in turn) or on the simulated DIGIT, a frame of each object under every\n"
    "setting of --grid and the backgrounds; runs `vkfuse study` on them; and writes\n"
    "the combination and method that improve sharpness, contrast and difference\n"
    "with background the most (on every object where one does) as FILE, which\n"
    "`vkfuse run --config FILE` uses. --keep DIR keeps the frames captured: how a\n"
    "real DIGIT's dataset for `vkfuse study` is recorded.",
    kOptions,
    "vkfuse tune --out digit.json && vkfuse run --config digit.json",
};

// A scratch directory for the captured dataset, removed whatever happens.
class ScratchDirectory {
public:
    ScratchDirectory() {
        std::string pattern = (std::filesystem::temp_directory_path() / "vkfuse-tune-XXXXXX").string();
        if (!::mkdtemp(pattern.data()))
            throw Error(ErrorKind::Io, "tune: cannot create a scratch directory in " +
                                           std::filesystem::temp_directory_path().string());
        path_ = pattern;
    }
    ~ScratchDirectory() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;
    std::string dataset() const { return path_ + "/dataset"; }

private:
    std::string path_;
};

// Waits for the person at the sensor: one line on stdin per object.
void ask_operator(const std::string& serial, const std::string& object) {
    if (object == "nothing")
        std::fprintf(stderr, "tune: take everything off %s's gel, keep it still, then press Enter\n", serial.c_str());
    else
        std::fprintf(stderr, "tune: press %s onto %s's gel and hold it still, then press Enter\n", object.c_str(),
                     serial.c_str());
    std::string line;
    if (!std::getline(std::cin, line))
        throw Error(ErrorKind::InvalidArgument, "tune: standard input closed while waiting for " + object);
}

// Where tune captures: the DIGIT named or plugged in (opened now, so its frame
// size is known), else the simulated DIGIT; and the objects pressed.
struct CaptureSource {
    std::vector<std::string> digits;  // empty: the simulated DIGIT
    std::optional<RunSensors> sensors;
    SensorInfo info;
    std::vector<std::string> objects;
};

CaptureSource choose_source(const Args& args) {
    CaptureSource src;
    if (auto v = args.value("--sensor")) src.digits = {*v};
    if (src.digits.empty() && !args.has("--simulate")) {
        src.digits = plugged_digits();
        if (src.digits.size() > 1) src.digits.resize(1);
    }
    if (src.digits.empty()) {
        src.objects = args.has("--objects") ? parse_sim_objects("--objects", *args.value("--objects"))
                                            : std::vector<std::string>{"coin", "lego"};
        src.info = SimDigit(SimDigitOptions{}).info();
        return src;
    }
    if (!args.has("--objects")) args.usage_error("--objects: name the objects you will press onto " + src.digits[0]);
    src.objects = split_list(*args.value("--objects"));
    src.sensors = digit_sensors(RunOptions{}, src.digits);
    src.info = src.sensors->rig.front().sensor->info();
    return src;
}

void capture(CaptureSource& src, const std::string& directory, RecordOptions rec, StopSignal& stop) {
    Progress progress("vkfuse tune");
    rec.progress = [&](std::size_t done, std::size_t total) {
        if (stop.requested()) throw Error(ErrorKind::InvalidArgument, "tune: interrupted; nothing written");
        progress.fraction(done, total, "frames");
    };
    rec.objects = src.objects;
    if (!src.sensors) {
        std::fprintf(stderr, "tune: no DIGIT plugged in; capturing from the simulated DIGIT\n");
        record_simulated(directory, SimDigitOptions{}, rec);
    } else {
        DatasetWriter writer(directory, "vkfuse tune");
        const std::string serial = src.digits[0];
        rec.place_object = [&](const std::string& object) { ask_operator(serial, object); };
        record_dataset(*src.sensors->rig.front().sensor, src.sensors->rig.front().clock, writer, rec);
        writer.finish();
    }
    progress.finish();
}

RunConfig winner(const StudyResult& r) {
    if (r.best.settings.empty())
        throw Error(ErrorKind::InvalidArgument, "tune: nothing was fused (a grid of one setting?)");
    RunConfig c;
    for (std::size_t s : r.best.settings) c.sequence.push_back(r.settings[s]);
    for (const StudyMethod& m : study_methods())
        if (m.name == r.best_best_method) c.fusion = m.spec;
    return c;
}

json::Value tuned_json(const StudyResult& r, const std::string& source) {
    json::Value::Array objects;
    for (const std::string& o : r.objects) objects.emplace_back(o);
    return json::Value::Object{{"source", source},
                               {"objects", std::move(objects)},
                               {"method", r.best_best_method},
                               {"sharpness_gain", r.best.gain.sharpness},
                               {"contrast_gain", r.best.gain.contrast},
                               {"background_diff_gain", r.best.gain.background_diff},
                               {"improves_all_on_every_object", r.best_improves_all_objects},
                               {"combinations", std::uint64_t(r.combinations)}};
}

int run(const Args& args) {
    if (!args.operands().empty()) args.usage_error("unexpected operand " + args.operands().front());
    if (args.has("--dataset"))
        for (const char* option : {"--sensor", "--simulate", "--grid", "--background-frames", "--keep"})
            if (args.has(option)) args.usage_error(std::string(option) + " does not apply to --dataset (the recording decides)");
    const std::string out = args.value("--out").value_or("vkfuse-config.json");
    StudyOptions options;
    options.max_k = args.has("--max-k") ? parse_positive_int("--max-k", *args.value("--max-k")) : 3;
    if (options.max_k < 2) args.usage_error("--max-k 1: a study fuses combinations of at least 2 settings");
    options.methods = parse_study_methods(args);
    const Backend backend = parse_backend_option(args.value("--backend").value_or("auto"));
    RecordOptions rec;
    rec.grid = parse_grid("--grid", args.value("--grid").value_or("0,15"));
    rec.background_frames =
        args.has("--background-frames") ? parse_positive_int("--background-frames", *args.value("--background-frames")) : 4;

    // Everything that could fail after the capture is checked before it, so
    // nobody presses objects for nothing.
    if (!args.has("--dataset")) {
        const LedLayout leds = LedLayout::digit();
        if (rec.grid.size() < 2) args.usage_error("--grid: one setting; a study fuses two or more");
        if (std::none_of(rec.grid.begin(), rec.grid.end(), [&](const Illumination& s) { return s.is_full(leds); }))
            args.usage_error("--grid: no level " + std::to_string(leds.max_level) +
                             ", so no static setting (every LED at full) to measure the gains against");
    }
    if (auto v = args.value("--objects"))
        for (const std::string& o : split_list(*v)) io::check_plain_component(o, "--objects");
    const std::filesystem::path parent = std::filesystem::absolute(out).parent_path();
    if (::access(parent.c_str(), W_OK) != 0)
        throw Error(ErrorKind::Io, out + ": cannot write in " + parent.string());
    std::optional<CaptureSource> source_of_frames;
    if (!args.has("--dataset")) {
        source_of_frames = choose_source(args);
        StudyShape shape{rec.grid.size(), source_of_frames->objects, source_of_frames->info.height,
                         source_of_frames->info.width};
        check_study_shape(shape, options,
                          "tune: --grid " + args.value("--grid").value_or("0,15") + " --max-k " +
                              std::to_string(options.max_k));
    }

    StopSignal stop;
    ScratchDirectory scratch;
    // --keep: captured into a staged directory, published once the capture
    // is complete (whatever the study then does); otherwise into scratch.
    std::optional<StagedDirectory> keep;
    if (auto v = args.value("--keep")) keep.emplace(*v, StagedDirectory::Policy{"--keep", false, nullptr, ""});
    std::string source, dataset_dir;
    if (auto v = args.value("--dataset")) {
        source = dataset_dir = *v;
        if (auto objects = args.value("--objects")) options.objects = split_list(*objects);
    } else {
        capture(*source_of_frames, keep ? keep->path() : scratch.dataset(), rec, stop);
        source = "captured now";
        dataset_dir = scratch.dataset();
        if (keep) {
            keep->publish();
            source = dataset_dir = keep->where();
        }
    }
    const Dataset dataset = read_dataset(dataset_dir);
    if (!dataset.incomplete.empty()) std::fprintf(stderr, "vkfuse tune: %s\n", dataset.incomplete.c_str());
    std::optional<Context> context = open_backend(backend);
    Progress progress("vkfuse tune");
    options.progress = [&](std::size_t done, std::size_t total) {
        if (stop.requested()) throw Error(ErrorKind::InvalidArgument, "tune: interrupted; nothing written");
        progress.status("study: " + std::to_string(done) + " / " + std::to_string(total) + " method x combination steps");
    };
    const StudyResult result = run_study(dataset, options, context ? &*context : nullptr);
    progress.finish();
    const RunConfig config = winner(result);
    const std::string text = run_config_json(config, tuned_json(result, source));
    char gains[160];
    std::snprintf(gains, sizeof gains, "sharpness x%.3f, contrast x%.3f, background difference x%.3f%s",
                  result.best.gain.sharpness, result.best.gain.contrast, result.best.gain.background_diff,
                  result.best_improves_all_objects ? ", better on every object" : "");
    // Reported before the file is written: a report that cannot be delivered
    // fails the command with nothing written.
    print_checked(out + ": " + to_string(config.sequence) + " fused by " + result.best_best_method + " (" + gains +
                  "); vkfuse run --config " + out + "\n");
    io::write_atomically(out, [&](std::FILE* f) { io::write_all(f, text, out); });
    return 0;
}

}  // namespace

const Command tune_command{kSpec, run};

}  // namespace vkfuse::cli

// vkfuse convert: a dataset from one form to the other (a folder of PNGs and
// its manifest, or one MCAP recording), every fact carried over.
#include <cstdio>

#include "commands.hpp"
#include "progress.hpp"
#include "staged_directory.hpp"
#include "standard_output.hpp"
#include "stop_signal.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::cli {
namespace {

constexpr OptionSpec kOptions[] = {
    {"--compression", "", "NAME", "an MCAP output's chunk compression: zstd (default), lz4 or none"},
};

constexpr CommandSpec kSpec{
    "convert",
    "convert a dataset between a folder (PNGs + manifest.json) and one MCAP file",
    "vkfuse convert IN OUT [--compression zstd|lz4|none]",
    "Reads the dataset IN (a folder, or a file ending in .mcap) and writes it as\n"
    "OUT, in the form OUT's name says: every sensor, take, frame (pixels, index,\n"
    "timestamp, LED setting, cycle), missed cycle and the recorded run carried\n"
    "over, so `vkfuse run --replay` plays both the same, bit for bit. A folder's\n"
    "PNG names are its own (numbered per sensor). OUT must not exist; it appears\n"
    "whole or not at all.",
    kOptions,
    "vkfuse convert rig-recording rig.mcap",
};

int run(const Args& args) {
    if (args.operands().size() != 2) args.usage_error("expected IN and OUT");
    const std::string in = args.operands()[0], out = args.operands()[1];
    DatasetWriterOptions options;
    options.compression = args.value("--compression").value_or("zstd");
    if (options.compression != "zstd" && options.compression != "lz4" && options.compression != "none")
        args.usage_error("--compression " + options.compression + ": expected zstd, lz4 or none");
    if (args.has("--compression") && !is_mcap_path(out))
        args.usage_error("--compression: OUT " + out + " is a folder (only an MCAP file is compressed)");
    StopSignal stop;
    const Dataset dataset = read_dataset(in);
    if (!dataset.incomplete.empty()) std::fprintf(stderr, "vkfuse convert: %s\n", dataset.incomplete.c_str());
    StagedDataset staged(out, "OUT");
    DatasetWriter writer(staged.path(), dataset.source, options);
    for (const DatasetSensorRecord& s : dataset.sensors) writer.add_sensor(s.info);
    if (dataset.run) writer.set_run(*dataset.run);
    std::size_t total = 0, done = 0, missed = 0;
    for (const DatasetSensorRecord& s : dataset.sensors)
        for (const DatasetTake& t : s.takes) total += t.frames.size();
    Progress progress("vkfuse convert");
    for (std::size_t i = 0; i < dataset.sensors.size(); ++i) {
        const DatasetSensorRecord& s = dataset.sensors[i];
        for (const DatasetTake& t : s.takes)
            for (const DatasetFrame& f : t.frames) {
                if (stop.requested()) throw Error(ErrorKind::InvalidArgument, "convert: interrupted; nothing written");
                writer.add_frame(int(i), t.object, t.background, load_frame(dataset, s, f), f.illumination, f.cycle);
                progress.fraction(++done, total, "frames");
            }
        for (const DatasetMiss& m : s.missed) writer.add_miss(int(i), m);
        missed += s.missed.size();
    }
    writer.finish();
    progress.finish();
    print_checked(out + ": " + std::to_string(dataset.sensors.size()) + " sensors, " + std::to_string(total) +
                  " frames, " + std::to_string(missed) + " missed cycles (from " + in + ")\n");
    staged.publish();
    return 0;
}

}  // namespace

const Command convert_command{kSpec, run};

}  // namespace vkfuse::cli

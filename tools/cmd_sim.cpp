// vkfuse sim: render a dataset from the simulated DIGIT.
#include <algorithm>
#include <cstdio>

#include "commands.hpp"
#include "progress.hpp"
#include "sim_record.hpp"
#include "staged_directory.hpp"
#include "standard_output.hpp"
#include "stop_signal.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/dataset.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::cli {
namespace {

constexpr OptionSpec kOptions[] = {
    {"--out", "", "DIR|FILE.mcap", "the dataset: a new directory, or one MCAP file (default sim-dataset)"},
    {"--objects", "", "A,B", "objects to press, in order (default every object but nothing)"},
    {"--grid", "", "V,V", "LED levels 0..15; every r,g,b combination is captured (default 0,1,5,15: 64 settings)"},
    {"--frames", "", "N", "frames per object and setting (default 1)"},
    {"--background-frames", "", "N", "no-contact frames per setting (default: as --frames)"},
    {"--seed", "", "N", "simulator seed (default 1)"},
    {"--vga", "", "", "VGA 640x480 at 30 fps instead of QVGA 320x240 at 60 fps"},
    {"--camera-auto", "", "", "the camera's auto exposure and white balance on (default: locked)"},
};

constexpr CommandSpec kSpec{
    "sim",
    "render a dataset (frames and backgrounds per object x illumination) from the simulated DIGIT",
    "vkfuse sim [--out DIR] [--objects A,B] [--grid V,V] [--frames N] [--vga]",
    "Presses each object into a simulated DIGIT and captures it under every LED\n"
    "setting of the grid, after the background (nothing pressed) under each. Only\n"
    "frames lit entirely by their setting are kept. Writes lossless PNGs and a\n"
    "manifest.json (see README, \"Datasets\"); `vkfuse run --replay DIR` plays it.",
    kOptions,
    "vkfuse sim --out coin-set --objects coin-heads,coin-tails --grid 0,15 --frames 4",
};

int run(const Args& args) {
    if (!args.operands().empty()) args.usage_error("unexpected operand " + args.operands().front());
    RecordOptions rec;
    rec.objects = args.has("--objects") ? parse_sim_objects("--objects", *args.value("--objects")) : every_sim_object();
    rec.grid = parse_grid("--grid", args.value("--grid").value_or("0,1,5,15"));
    rec.frames = args.has("--frames") ? parse_positive_int("--frames", *args.value("--frames")) : 1;
    rec.background_frames = args.has("--background-frames")
                                ? parse_positive_int("--background-frames", *args.value("--background-frames"))
                                : rec.frames;
    SimDigitOptions sim_options;
    sim_options.vga = args.has("--vga");
    sim_options.camera_auto = args.has("--camera-auto");
    if (auto v = args.value("--seed")) sim_options.seed = std::uint64_t(parse_count("--seed", *v));
    const std::string out = args.value("--out").value_or("sim-dataset");
    // Written beside its name and renamed into place when complete: an
    // interrupted or failed recording leaves nothing behind.
    StopSignal stop;
    StagedDataset staged(out, "--out");
    Progress progress("vkfuse sim");
    rec.progress = [&](std::size_t done, std::size_t total) {
        if (stop.requested()) throw Error(ErrorKind::InvalidArgument, "--out " + out + ": interrupted; nothing written");
        progress.fraction(done, total, "frames");
    };
    record_simulated(staged.path(), sim_options, rec);
    progress.finish();
    // Reported before it is published: a report that cannot be delivered
    // (a full disk, a closed pipe) fails the command with nothing written.
    print_checked(out + ": " + std::to_string(rec.objects.size()) + " objects x " + std::to_string(rec.grid.size()) +
                  " settings, " + std::to_string(rec.background_frames) + " + " + std::to_string(rec.frames) +
                  " frames each (background + object)\n");
    staged.publish();
    return 0;
}

}  // namespace

const Command sim_command{kSpec, run};

}  // namespace vkfuse::cli

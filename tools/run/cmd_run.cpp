// vkfuse run: sensors cycling through an LED sequence, fused every cycle.
#include <chrono>
#include <cstdio>
#include <memory>

#include "shared_options.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "run/run_options.hpp"
#include "run/run_output.hpp"
#include "run/run_publish.hpp"
#ifdef VKFUSE_WITH_SERVE
#include "serve/live_server.hpp"
#endif
#include "run/run_session.hpp"
#include "run/run_stats.hpp"
#include "staged_directory.hpp"
#include "standard_output.hpp"
#include "stop_signal.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {
namespace {

constexpr OptionSpec kOptions[] = {
    {"--sensor", "", "DEV", "a real DIGIT by serial (D20001) or video node (/dev/video0); repeat for several (default: every DIGIT plugged in, else simulated ones)"},
    {"--encoding", "", "E", "how real DIGITs stream: yuyv or mjpeg (default yuyv)"},
    {"--simulate", "", "", "simulate DIGITs even when real ones are plugged in"},
    {"--sensors", "", "N", "simulated DIGITs, serials SIM-0001.. (default 1)"},
    {"--object", "", "NAME", "what is pressed into the gel (default coin; see below)"},
    {"--motion", "", "M", "how it moves: still, tap (pressed half of each period) or slide (default still)"},
    {"--motion-period", "", "SECONDS", "one tap, or one slide across the gel and back (default 2)"},
    {"--sequence", "", "SEQ", "LED settings per cycle, r,g,b each 0..15, joined by + (default 15,15,15+0,15,0)"},
    {"--config", "", "FILE", "the sequence and fusion `vkfuse tune` chose; options given here win over it"},
    {"--method", "", "M", "{methods} (default wavelet)"},
    kLevelsOption,
    kWaveletOption,
    kModeOption,
    kBaseRuleOption,
    kDetailRuleOption,
    kBackendOption,
    {"--cycles", "", "N", "stop after N cycles (default: until Ctrl-C; a replay: every recorded cycle)"},
    {"--duration", "", "SECONDS", "stop once the fused frames span this much sensor time"},
    {"--virtual-clock", "", "", "simulate on virtual clocks: as fast as the host allows, deterministic"},
    {"--camera-auto", "", "", "simulate the camera's auto exposure and white balance (default: locked)"},
    {"--background-frames", "", "N", "no-contact frames averaged per setting for the background (default 20; 0: none)"},
    {"--skip", "", "MODE", "off; idle: a sensor whose frames stay within its background noise is not fused; static: also one whose frames match its last fused cycle; tiles: also a changed sensor fuses only its changed tiles and their halo (default tiles)"},
    {"--skip-threshold", "", "K", "a tile changed when a sample lies over K x the tile's noise from the background (default 8)"},
    {"--cycles-in-flight", "", "N", "1: each cycle is fused and written before the next is fused; 2: the GPU fuses cycle c + 1 while cycle c is written (needs --skip off; the CPU path keeps 1) (default 1)"},
    {"--window", "", "cycle|sliding", "cycle: one clean frame per setting, fused once per cycle (the paper's way); sliding: the newest clean frame of each setting, fused at every new clean frame, K times the fused rate (live sensors; a replay plays the windows as they were recorded) (default cycle; a replay: the recording's)"},
    {"--switch-priority", "", "N", "live sensors: each LED switch request runs under real-time scheduling (SCHED_FIFO) at this priority, 1..99, for the moment it takes, since a request has about a millisecond of slack and a busy host wakes a normal thread later, losing a frame; 0: the normal scheduler. Refused (no CAP_SYS_NICE or RLIMIT_RTPRIO), the run goes on as with 0 and summary.json's switch_scheduling says so (default 10)"},
    {"--metrics", "", "LIST", "the metrics computed and written, comma-separated: sharpness, contrast, background_diff (default all three; background_diff needs a background)"},
    {"--pressing", "", "N", "simulated DIGITs: only the first N press --object, the rest touch nothing (default all)"},
    {"--timeout", "", "SECONDS", "how long a cycle waits for a late sensor (default 5; 120 with --virtual-clock or --replay)"},
    {"--replay", "", "DIR|FILE.mcap", "play a recorded dataset instead of simulating (vkfuse sim, vkfuse run --record)"},
    {"--realtime", "", "", "with --replay: decode every frame first, then hand each over at the pace it was recorded, as the sensors did (default: as fast as the host fuses)"},
    {"--record", "", "DIR|FILE.mcap", "record the frames fused (and the background frames) as a dataset: a new directory, or one MCAP file (ROS 2 types, zstd)"},
    {"--out", "", "DIR", "write fused PNGs, metrics.jsonl, side-by-side pictures, summary.json (a new directory)"},
    {"--replace", "", "", "let --out name a previous run's directory: replaced whole once this run succeeds"},
    {"--publish", "", "ros2", "also publish every cycle on ROS 2's wire (DDS): /vkfuse/<serial>/fused, /vkfuse/<serial>/metrics, /vkfuse/rig, /diagnostics (see README, \"Rigs across machines\")"},
    {"--serve", "", "[ADDR:]PORT", "serve a live page of the rig and the Foxglove WebSocket protocol on this port (address 127.0.0.1 unless given; port 0: any free one, printed) (see README, \"Watching a rig\")"},
    {"--ros-domain", "", "N", "the ROS 2 domain to publish in, 0..232 (default: ROS_DOMAIN_ID, else 0)"},
    {"--publish-encoding", "", "E", "fused images as rgb8 (the samples of --out's PNGs) or 32FC3 (float32) (default rgb8)"},
    {"--publish-wait", "", "SECONDS", "before the first cycle, wait this long at most for subscribers to every topic each sensor publishes per cycle (default 0)"},
    {"--publish-frames", "", "", "with --publish ros2: also each sensor's cycles (/vkfuse/<serial>/cycle) and background (/vkfuse/<serial>/background), for a fusion host (--source ros2)"},
    {"--capture-only", "", "", "a capture host: capture and publish (--publish ros2 --publish-frames) or record the cycles, fuse nothing (no Vulkan device needed)"},
    {"--source", "", "ros2", "fuse the sensors a capture host publishes on ROS 2's wire (in --ros-domain) instead of local ones; --sensor SERIAL picks some (default: every sensor of the first capture host heard)"},
    {"--queue", "", "N", "with --source ros2: cycles each sensor keeps when fusion falls behind, the oldest dropped first (default 4: results stay fresh; more rides out longer stalls)"},
    {"--startup-timeout", "", "SECONDS", "how long the start waits for sensors to calibrate and take their backgrounds, and with --source ros2 for the capture host (default 60)"},
};

static_assert(SkipConfig{}.threshold == 8.0, "--skip-threshold's help states the default");

constexpr CommandSpec kSpec{
    "run",
    "drive real, simulated or recorded DIGITs through an LED sequence and fuse every cycle",
    "vkfuse run [options]",
    "Each sensor cycles through the LED settings of --sequence on its own capture\n"
    "thread; every cycle takes one frame lit entirely by each setting (LED latency\n"
    "and rolling shutter are measured at start-up) and fuses all sensors with one\n"
    "GPU submit. It drives the DIGITs plugged in (or those --sensor names; one\n"
    "unplugged mid-run is reported failed each cycle until it is back), and\n"
    "without any it says so and simulates DIGITs pressing --object\n"
    "(nothing, coin, coin-heads, coin-tails, lego, ball, screw, nut, velcro, file,\n"
    "text). A live line on stderr shows fused fps and per-stage latency; Ctrl-C\n"
    "or SIGTERM finishes the cycle in hand and writes the files. Prints a JSON\n"
    "summary. --out and --record are written beside their names and appear whole\n"
    "when the run succeeds; a failed run leaves no trace and changes no file. A\n"
    "run that fused no cycle (stopped before its first) has failed, and so has a\n"
    "--record without a whole cycle of every sensor (it could not be replayed).",
    kOptions,
    "vkfuse run --sensors 4 --cycles 120 --virtual-clock --out out",
};

// The rig's sources (run_session.hpp) and what this run writes.
struct Session : RigSession {
    // Declared before what writes into them: destroyed (removed unless
    // published) after the writers have closed their files.
    std::unique_ptr<StagedDirectory> out_dir;
    std::unique_ptr<StagedDataset> record;  // --record: a directory or one .mcap file
    std::unique_ptr<DatasetWriter> recorder;
    std::unique_ptr<RunOutput> output;
    std::unique_ptr<RunPublisher> publisher;  // --publish
#ifdef VKFUSE_WITH_SERVE
    std::unique_ptr<serve::LiveServer> server;  // --serve
#endif
};

// The target directories are checked (and their staging directories made)
// before anything else happens, so a run that cannot write fails at once.
void stage_outputs(Session& s, const Args& args) {
    const RunOptions& o = s.options;
    if (args.has("--replace") && !o.out) throw Error(ErrorKind::InvalidArgument, "--replace: needs --out");
    if (o.out)
        s.out_dir = std::make_unique<StagedDirectory>(
            *o.out, StagedDirectory::Policy{"--out", args.has("--replace"), is_run_output_entry, "--replace"});
    if (o.record) {
        s.record = std::make_unique<StagedDataset>(*o.record, "--record");
        if (s.out_dir && s.out_dir->where() == s.record->where())
            throw Error(ErrorKind::InvalidArgument, "--record " + *o.record + ": the same directory as --out");
    }
}

Session prepare(const Args& args) {
    Session s;
    s.options = parse_run_options(args);
    stage_outputs(s, args);
    open_sources(s, args);
    return s;
}

RigConfig rig_config(Session& s) {
    RigConfig cfg = rig_config(static_cast<const RigSession&>(s));
    // The recorder and the output are made once the rig has accepted the
    // configuration (no directory for a run that cannot start); the callback
    // finds them then.
    std::vector<std::string> serials;
    for (const RigSensor& r : s.sensors.rig) serials.push_back(r.sensor->info().serial);
    if (s.options.record || s.options.publish_frames || s.options.out)
        cfg.on_background = [&rec = s.recorder, &pub = s.publisher, &out = s.output, serials](
                                std::size_t i, const Illumination& setting, const std::vector<Frame>& frames) {
            if (rec)
                for (const Frame& f : frames) rec->add_frame(int(i), "nothing", true, f, setting);
            if (pub) pub->publish_background(i, setting, frames);
            if (out) out->add_background(serials.at(i), setting, frames);
        };
    return cfg;
}

// Files are opened only now, after every check has passed, in the staging
// directories.
void open_outputs(Session& s) {
    const RunOptions& o = s.options;
    if (s.out_dir)
        s.output = std::make_unique<RunOutput>(
            s.out_dir->path(), o.object,
            RunOutputLabels{o.sequence, static_slot(o.sequence, s.sensors.rig.front().sensor->info().leds),
                            method_label(o.fusion), o.metrics},
            o.skip.policy != SkipPolicy::Off);
    if (!s.record) return;
    s.recorder = std::make_unique<DatasetWriter>(s.record->path(), "vkfuse run");
    for (const RigSensor& r : s.sensors.rig) s.recorder->add_sensor(r.sensor->info());
    s.recorder->set_run({s.options.sequence, s.options.fusion, s.options.background_frames, s.options.window});
}

// --serve: listening before the rig starts, so a page opened now sees its first cycle.
void start_server(Session& s) {
#ifdef VKFUSE_WITH_SERVE
    if (!s.options.serve) return;
    const RunOptions& o = s.options;
    serve::LiveRig live;
    for (const RigSensor& r : s.sensors.rig) live.sensors.push_back(r.sensor->info());
    live.sequence = o.sequence;
    live.method = method_label(o.fusion);
    live.object = o.object;
    live.static_slot = static_slot(o.sequence, live.sensors.front().leds);
    live.skipping = o.skip.policy != SkipPolicy::Off;
    const serve::ServeAddress address = serve::parse_serve_address(*o.serve);
    s.server = std::make_unique<serve::LiveServer>(address, serve::LiveChannels(live));
    const std::string host = address.host.find(':') != std::string::npos ? "[" + address.host + "]" : address.host;
    std::fprintf(stderr, "vkfuse run: serving http://%s:%u/ (Foxglove: ws://%s:%u)\n", host.c_str(),
                 unsigned(s.server->port()), host.c_str(), unsigned(s.server->port()));
#else
    (void)s;
#endif
}

void record_cycle(DatasetWriter& rec, const CycleResult& cycle, const RunOptions& o) {
    for (std::size_t i = 0; i < cycle.sensors.size(); ++i) {
        const SensorCycle& s = cycle.sensors[i];
        if (s.status != SensorStatus::Ok) {
            rec.add_miss(int(i), {std::int64_t(cycle.cycle), std::string(to_string(s.status)), s.error});
            continue;
        }
        for (std::size_t k = 0; k < s.frames.size(); ++k)
            rec.add_frame(int(i), o.object, false, s.frames[k], o.sequence[k], std::int64_t(cycle.cycle));
    }
}

bool more_to_do(const Session& s, const Rig& rig, const RunStats& stats, const StopSignal& stop) {
    const std::optional<int> target = cycle_target(s);
    if (stop.requested()) return false;
    // With every sensor failed, one cycle is still taken when none was yet:
    // it carries the sensors' errors, which end the run with one line.
    if (rig.all_failed()) return stats.cycles() == 0;
    if (target && stats.cycles() >= std::uint64_t(*target)) return false;
    return !(s.options.duration_s && stats.sensor_elapsed_s() >= *s.options.duration_s);
}

RunStats cycle_loop(Session& s, Rig& rig, const StopSignal& stop) {
    RunStats stats(rig.sensors(), s.options.skip);
    Progress progress("vkfuse run");
    while (more_to_do(s, rig, stats, stop)) {
        CycleResult cycle = rig.next();
        if (s.dataset) report_as_recorded(cycle, *s.dataset);
        const auto write_start = std::chrono::steady_clock::now();
        if (s.output) s.output->write(cycle);
        if (s.publisher) s.publisher->publish(cycle);
#ifdef VKFUSE_WITH_SERVE
        if (s.server) s.server->publish(cycle);
#endif
        if (s.recorder) record_cycle(*s.recorder, cycle, s.options);
        stats.add(cycle, std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count());
        if (stats.fused() == 0 && rig.all_failed()) break;  // the run fails with the sensors' error alone
        progress.status(stats.progress_line(cycle_target(s)));
    }
    progress.finish();
    return stats;
}

// What the run leaves untouched when it has nothing to publish, for its one line.
std::string left_as_they_were(const Session& s) {
    std::string kept;
    if (s.out_dir) kept = "--out " + s.out_dir->target();
    if (s.record) kept += (kept.empty() ? "--record " : " and --record ") + s.record->target();
    return kept.empty() ? "" : "; " + kept + " left as " + (s.out_dir && s.record ? "they were" : "it was");
}

// A run publishes only results it can stand behind: at least one fused cycle,
// and a recording that `run --replay` can play (backgrounds, which the rig
// takes before its first cycle, and a whole cycle of every sensor). Anything
// less fails the run, and nothing is published or replaced.
void require_results(const Session& s, const RunStats& stats, bool interrupted) {
    if (stats.fused() == 0) {
        if (!stats.errors().empty()) throw Error(ErrorKind::Device, *stats.errors().begin());
        throw Error(ErrorKind::InvalidArgument, std::string(interrupted ? "interrupted" : "stopped") +
                                                    " before any cycle was fused; nothing written" +
                                                    left_as_they_were(s));
    }
    if (!s.recorder) return;
    for (std::size_t i = 0; i < s.sensors.rig.size(); ++i)
        if (stats.fused(i) == 0) {
            const std::string& why = stats.last_error(i);
            throw Error(ErrorKind::InvalidArgument,
                        "--record " + s.record->target() + ": " + s.sensors.rig[i].sensor->info().serial +
                            " delivered no whole cycle" + (why.empty() ? "" : " (" + why + ")") +
                            ", so the recording could not be replayed; nothing written" + left_as_they_were(s));
        }
}

int run(const Args& args) {
    // First, so a signal at any point ends the run the orderly way.
    StopSignal stop;
    Session s = prepare(args);
    // A capture host fuses nothing: no device is opened.
    std::optional<Context> context = s.options.capture_only ? std::nullopt : open_backend(s.options.backend);
    if (!context && s.options.cycles_in_flight != 1) {
        std::fprintf(stderr, "vkfuse run: --cycles-in-flight %d: the CPU path fuses each cycle as it is taken; 1 cycle in flight\n",
                     s.options.cycles_in_flight);
        s.options.cycles_in_flight = 1;
    }
    Rig rig(context ? &*context : nullptr, rig_config(s), s.sensors.rig);
    open_outputs(s);
    s.publisher = RunPublisher::make(s.options, s.sensors.rig);
    // Before the rig starts: a background goes out to subscribers already
    // matched, as a live sample (one written before a subscriber matched
    // reaches it only as history, which a capture host that exits at once
    // can take away with it).
    if (s.publisher) s.publisher->wait_for_subscribers();
    start_server(s);
    rig.start();
    const RunStats stats = cycle_loop(s, rig, stop);
    const std::string summary = stats.summary_json(rig, source_summary(s.sensors));
    require_results(s, stats, stop.requested());
    if (s.recorder) s.recorder->finish();
    if (s.output) s.output->finish(summary);
    // Without --out the summary on stdout is the only result: a failed write
    // (a full disk, a closed pipe) fails the run like any other lost output.
    print_checked(summary + "\n");
    if (s.record) s.record->publish();
    if (s.out_dir) s.out_dir->publish();
    if (stop.requested())
        std::fprintf(stderr, "vkfuse run: interrupted after %llu cycle%s; wrote what they fused\n",
                     static_cast<unsigned long long>(stats.cycles()), stats.cycles() == 1 ? "" : "s");
    return 0;
}

}  // namespace

const Command run_command{kSpec, run};

}  // namespace vkfuse::cli

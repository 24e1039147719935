// The sources and rig configuration of `vkfuse run` (run_session.hpp).
#include "run/run_session.hpp"

#include <cstdio>
#include <filesystem>

#include "memory_check.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {
namespace {

// A replayed manifest says how large its frames are: before any buffer is
// sized from that, the rig's memory is checked against what the process may
// take. Per sensor, its fusion and frames are bounded like a `vkfuse fuse` of
// K frames of that shape, plus three cycles of 8-bit frames in flight (the
// capture, the mailbox, the last good cycle) and the background means.
void require_replay_memory(const RunOptions& o, const std::shared_ptr<const Dataset>& recording) {
    const Dataset& dataset = *recording;
    const std::uint64_t K = o.sequence.size();
    std::uint64_t need = 0;
    for (const DatasetSensorRecord& r : dataset.sensors) {
        io::ImageHeader frame;
        frame.height = r.info.height;
        frame.width = r.info.width;
        frame.channels = 3;
        need += fuse_memory_need(std::vector<io::ImageHeader>(K, frame), o.fusion.method, o.backend);
        need += K * (3 * frame.samples() + frame.image_bytes());
        // --realtime holds every frame it plays, decoded.
        if (o.realtime)
            need += DatasetSensor(recording, r.info.serial, o.object).frames() * frame.samples();  // 8-bit samples
    }
    require_memory({(std::filesystem::path(dataset.directory) / "manifest.json").string()}, "replaying", need);
}

// Real DIGITs when named or plugged in, else simulated ones. A choice made
// without being asked for is said in one line.
void choose_live_sensors(RigSession& s, const Args& args) {
    RunOptions& o = s.options;
    if (!o.digits.empty()) {
        s.sensors = digit_sensors(o, o.digits);
    } else if (const std::vector<std::string> plugged = o.simulate ? std::vector<std::string>{} : plugged_digits();
               !plugged.empty()) {
        s.sensors = digit_sensors(o, plugged);
        std::string list;
        for (const std::string& serial : plugged) list += (list.empty() ? "" : ", ") + serial;
        std::fprintf(stderr, "vkfuse run: using the DIGIT%s plugged in: %s (--simulate to simulate instead)\n",
                     plugged.size() > 1 ? "s" : "", list.c_str());
    } else {
        s.sensors = simulated_sensors(o);
        if (!o.simulate)
            std::fprintf(stderr, "vkfuse run: no DIGIT found; simulating %d DIGIT%s (%s)\n", o.sensors,
                         o.sensors > 1 ? "s" : "", s.sensors.rig.front().sensor->info().serial.c_str());
        return;
    }
    o.sensors = int(s.sensors.rig.size());
    if (!args.has("--object")) o.object = "live";  // a label only: nothing tells what touches a real gel
}

}  // namespace

void open_sources(RigSession& s, const Args& args) {
    if (s.options.source_ros2) {
        s.sensors = remote_sensors(s.options, args);
    } else if (s.options.replay) {
        s.dataset = std::make_shared<const Dataset>(read_dataset(*s.options.replay));
        if (!s.dataset->incomplete.empty()) std::fprintf(stderr, "vkfuse run: %s\n", s.dataset->incomplete.c_str());
        adopt_recording(s.options, args, *s.dataset);
        require_replay_memory(s.options, s.dataset);
        s.sensors = replayed_sensors(s.options, s.dataset);
        if (s.sensors.recorded_cycles == 0)
            throw Error(ErrorKind::InvalidArgument, "--replay " + *s.options.replay + ": no full cycle of " +
                                                        to_string(s.options.sequence) + " recorded for " +
                                                        s.options.object);
    } else {
        choose_live_sensors(s, args);
    }
}

RigConfig rig_config(const RigSession& s) {
    const RunOptions& o = s.options;
    RigConfig cfg;
    cfg.fusion = o.fusion;
    cfg.sequence = o.sequence;
    cfg.judging = s.sensors.judging;
    cfg.background_frames = o.background_frames;
    cfg.cycle_timeout_s = o.timeout_s;
    cfg.startup_timeout_s = o.startup_timeout_s;
    cfg.fuse = !o.capture_only;
    cfg.want_fused = o.out.has_value() || o.publish_ros2 || o.serve.has_value();
    cfg.skip = o.skip;
    cfg.metrics = o.metrics;
    cfg.watch_when_idle = !o.record;  // a dataset holds every setting of every cycle
    cfg.cycles_in_flight = o.cycles_in_flight;
    cfg.switch_priority = o.switch_priority;
    cfg.window = o.window;
    if (!s.sensors.sims.empty() && o.background_frames > 0)
        cfg.after_background = [sims = s.sensors.sims, object = o.object,
                                pressing = std::size_t(o.pressing.value_or(o.sensors))](std::size_t i) {
            if (i < pressing) sims[i]->set_object(object);
        };
    return cfg;
}

std::optional<int> cycle_target(const RigSession& s) {
    if (s.options.cycles) return s.options.cycles;
    if (s.sensors.recorded_cycles) return int(*s.sensors.recorded_cycles);
    return std::nullopt;
}

}  // namespace vkfuse::cli

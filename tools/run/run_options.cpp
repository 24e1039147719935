#include "run/run_options.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "shared_options.hpp"
#include "run/run_config.hpp"
#include "sim_record.hpp"
#include "vkfuse/core/error.hpp"
#ifdef VKFUSE_WITH_SERVE
#include "serve/live_server.hpp"
#endif
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::cli {
namespace {

[[noreturn]] void fail(const std::string& message) { throw Error(ErrorKind::InvalidArgument, message); }

#ifdef VKFUSE_WITH_ROS2
constexpr bool kBuiltWithRos2 = true;
#else
constexpr bool kBuiltWithRos2 = false;
#endif

// --serve: its address checked now; a vkfuse built without Boost.Beast refuses it with one line.
void serve_option(const Args& args, RunOptions& o) {
    o.serve = args.value("--serve");
    if (!o.serve) return;
#ifdef VKFUSE_WITH_SERVE
    serve::parse_serve_address(*o.serve);
#else
    args.usage_error("--serve: this vkfuse was built without the live server (Boost.Beast: apt-get install "
                     "libboost1.81-dev, then rebuild)");
#endif
}

std::string format_seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%g s", s);
    return text;
}

IlluminationSequence sequence_option(const std::string& text, const LedLayout& leds) {
    try {
        IlluminationSequence seq = parse_sequence(text);
        for (const Illumination& s : seq) s.check(leds);
        return seq;
    } catch (const Error& e) {
        // A sequence past the bound is named by its start: the line stays short.
        fail("--sequence " + (text.size() > 64 ? text.substr(0, 64) + "..." : text) + ": " + e.what());
    }
}

void check_replay_conflicts(const Args& args) {
    for (const char* option : kSimulatorOptions)
        if (args.has(option))
            args.usage_error(std::string(option) + " does not apply to --replay (the recording decides)");
    for (const char* option : {"--background-frames", "--sensor", "--encoding", "--config"})
        if (args.has(option))
            args.usage_error(std::string(option) + " does not apply to --replay (the recording decides)");
}

// --sensor names real DIGITs: nothing that only the simulator takes applies.
void check_digit_conflicts(const Args& args) {
    for (const char* option : kSimulatorOptions)
        if (args.has(option)) args.usage_error(std::string(option) + " does not apply to real DIGITs (--sensor)");
}

// base, or base with the method --method names.
FusionSpec with_method(const Args& args, FusionSpec base) {
    if (auto v = args.value("--method")) base.method = parse_method(*v);
    return base;
}

void metric_options(const Args& args, RunOptions& o) {
    const bool background = o.background_frames > 0;
    o.metrics = MetricSet::all().with(Metric::BackgroundDiff, background);
    const auto v = args.value("--metrics");
    if (!v) return;
    const std::optional<MetricSet> asked = MetricSet::parse(*v);
    if (!asked) fail("--metrics " + *v + ": expected a comma-separated list of " + MetricSet::all().to_string());
    if (asked->has(Metric::BackgroundDiff) && !background)
        fail("--metrics " + *v + ": background_diff needs a background (--background-frames of at least 1)");
    o.metrics = *asked;
}

constexpr int kMaxSourceQueue = 64;

void require_ros2(const std::string& option) {
    if (!kBuiltWithRos2)
        fail(option + ": this vkfuse was built without ROS 2 support (Cyclone DDS: apt-get install "
                      "cyclonedds-dev cyclonedds-tools, then build again)");
}

// --source ros2: the sensors are another host's; what it decides is not
// for the command line here.
void source_options(const Args& args, RunOptions& o) {
    const std::optional<std::string> source = args.value("--source");
    if (!source) {
        if (args.has("--queue")) args.usage_error("--queue needs --source ros2");
        return;
    }
    if (*source != "ros2") fail("--source " + *source + ": expected ros2");
    require_ros2("--source ros2");
    for (const char* option : kSimulatorOptions)
        if (args.has(option)) args.usage_error(std::string(option) + " does not apply to --source ros2 (its sensors are another host's)");
    for (const char* option : {"--replay", "--sequence", "--background-frames", "--encoding", "--config", "--window"})
        if (args.has(option))
            args.usage_error(std::string(option) + " does not apply to --source ros2 (the capture host decides)");
    for (const char* option : {"--capture-only", "--publish-frames"})
        if (args.has(option))
            args.usage_error(std::string(option) + " does not apply to --source ros2 (the capture host publishes the frames)");
    o.source_ros2 = true;
    if (auto v = args.value("--queue")) {
        o.source_queue = parse_positive_int("--queue", *v);
        if (o.source_queue > kMaxSourceQueue)
            fail("--queue " + *v + ": at most " + std::to_string(kMaxSourceQueue) + " cycles");
    }
}

// --capture-only: a capture host, whose cycles go somewhere whole.
void capture_only_options(const Args& args, const RunOptions& o) {
    if (!o.capture_only) return;
    if (!o.publish_frames && !o.record)
        args.usage_error("--capture-only: needs --publish ros2 --publish-frames or --record (the cycles would go nowhere)");
    if (o.out) args.usage_error("--capture-only: --out holds fused images, and nothing is fused");
    for (const char* option : {"--skip", "--skip-threshold", "--metrics", "--cycles-in-flight", "--publish-encoding"})
        if (args.has(option)) args.usage_error(std::string(option) + " does not apply to --capture-only (nothing is fused)");
}

// The ROS 2 domain: --ros-domain, else ROS_DOMAIN_ID, else 0.
void domain_option(const Args& args, RunOptions& o) {
    const std::optional<std::string> domain = args.value("--ros-domain");
    const char* environment = std::getenv("ROS_DOMAIN_ID");
    const std::string text = domain ? *domain : environment ? environment : "";
    if (!domain && text.empty()) {
        o.ros_domain = 0;
    } else if (const std::optional<int> d = ros2::parse_domain(text)) {
        o.ros_domain = *d;
    } else {
        fail(std::string(domain ? "--ros-domain " : "ROS_DOMAIN_ID=") + text.substr(0, 32) + ": expected a domain 0.." +
             std::to_string(ros2::kMaxDomain));
    }
}

// --publish and what goes with it. A vkfuse built without Cyclone DDS
// refuses --publish ros2 with one line.
void publish_options(const Args& args, RunOptions& o) {
    const std::optional<std::string> publish = args.value("--publish");
    if (!publish) {
        for (const char* option : {"--publish-encoding", "--publish-wait", "--publish-frames"})
            if (args.has(option)) args.usage_error(std::string(option) + " needs --publish ros2");
        if (args.has("--ros-domain") && !o.source_ros2) args.usage_error("--ros-domain needs --publish ros2 or --source ros2");
        if (o.source_ros2) domain_option(args, o);
        return;
    }
    if (*publish != "ros2") fail("--publish " + *publish + ": expected ros2");
    require_ros2("--publish ros2");
    o.publish_ros2 = true;
    domain_option(args, o);
    o.publish_frames = args.has("--publish-frames");
    if (auto v = args.value("--publish-encoding")) {
        const std::optional<ros2::ImageEncoding> e = ros2::parse_image_encoding(*v);
        if (!e) fail("--publish-encoding " + *v + ": expected rgb8 or 32FC3");
        o.publish_encoding = *e;
    }
    if (auto v = args.value("--publish-wait")) o.publish_wait_s = parse_seconds("--publish-wait", *v);
}

}  // namespace

void background_options(const Args& args, RunOptions& o) {
    // A capture host skips nothing: its fusion host decides.
    o.skip.policy = o.background_frames >= 2 && !o.capture_only ? SkipPolicy::Tiles : SkipPolicy::Off;
    if (auto v = args.value("--skip")) {
        const std::optional<SkipPolicy> p = parse_skip_policy(*v);
        if (!p) fail("--skip " + *v + ": expected off, idle, static or tiles");
        if (*p != SkipPolicy::Off && o.background_frames < 2)
            fail("--skip " + *v + ": needs --background-frames of at least 2 (the noise each tile is judged by)");
        o.skip.policy = *p;
    }
    if (auto v = args.value("--skip-threshold")) {
        o.skip.threshold = parse_positive_number("--skip-threshold", *v);
        if (o.skip.policy == SkipPolicy::Off) fail("--skip-threshold " + *v + ": skipping is off");
    }
    if (auto v = args.value("--cycles-in-flight")) {
        o.cycles_in_flight = parse_positive_int("--cycles-in-flight", *v);
        if (o.cycles_in_flight > 2) fail("--cycles-in-flight " + *v + ": expected 1 or 2");
        if (o.cycles_in_flight == 2 && o.skip.policy != SkipPolicy::Off)
            fail("--cycles-in-flight 2: needs --skip off (a skipping plan keeps its references and held results "
                 "once, for 1 cycle in flight)");
    }
    if (auto v = args.value("--switch-priority")) {
        o.switch_priority = parse_count("--switch-priority", *v);
        if (o.switch_priority > 99) fail("--switch-priority " + *v + ": expected 0..99");
    }
    metric_options(args, o);
}

RunOptions parse_run_options(const Args& args) {
    if (!args.operands().empty()) args.usage_error("unexpected operand " + args.operands().front());
    RunOptions o;
    source_options(args, o);
    o.capture_only = args.has("--capture-only");
    o.replay = args.value("--replay");
    if (o.replay) check_replay_conflicts(args);
    o.realtime = args.has("--realtime");
    if (o.realtime && !o.replay) args.usage_error("--realtime needs --replay (live sensors keep their own pace)");
    o.digits = args.values("--sensor");
    if (!o.digits.empty() && !o.source_ros2) check_digit_conflicts(args);
    for (const char* option : kSimulatorOptions) o.simulate = o.simulate || args.has(option);
    if (auto v = args.value("--encoding")) o.encoding = parse_digit_encoding(*v, "--encoding");
    if (auto v = args.value("--sensors")) o.sensors = parse_positive_int("--sensors", *v);
    if (o.sensors > kMaxSimulatedSensors)
        fail("--sensors " + std::to_string(o.sensors) + ": at most " + std::to_string(kMaxSimulatedSensors));
    if (auto v = args.value("--object")) o.object = *v;
    if (!o.replay && !o.source_ros2) check_sim_object("--object " + o.object, o.object);
    if (auto v = args.value("--motion")) o.motion = parse_sim_motion(*v);
    if (auto v = args.value("--motion-period")) {
        o.motion_period_s = parse_seconds("--motion-period", *v);
        if (o.motion_period_s < SimDigitOptions::kMinMotionPeriodS)
            fail("--motion-period " + *v + ": shorter than the simulator's shortest motion period (" +
                 format_seconds(SimDigitOptions::kMinMotionPeriodS) + ")");
    }
    // A tuned configuration stands in for the defaults; what the command
    // line says wins over both.
    std::optional<RunConfig> config;
    if (auto v = args.value("--config")) config = read_run_config(*v);
    o.sequence = args.has("--sequence") || !config
                     ? sequence_option(args.value("--sequence").value_or(kDefaultSequence), LedLayout::digit())
                     : config->sequence;
    o.fusion = fusion_options(args, with_method(args, config ? config->fusion : FusionSpec{}));
    o.backend = parse_backend_option(args.value("--backend").value_or("auto"));
    if (auto v = args.value("--cycles")) o.cycles = parse_positive_int("--cycles", *v);
    if (auto v = args.value("--duration")) o.duration_s = parse_seconds("--duration", *v);
    if (auto v = args.value("--window")) o.window = parse_fusion_window(*v);
    o.virtual_clock = args.has("--virtual-clock");
    o.camera_auto = args.has("--camera-auto");
    o.record = args.value("--record");
    o.out = args.value("--out");
    o.background_frames = kDefaultBackgroundFrames;
    if (auto v = args.value("--background-frames")) o.background_frames = parse_count("--background-frames", *v);
    background_options(args, o);
    if (auto v = args.value("--pressing")) {
        o.pressing = parse_count("--pressing", *v);
        if (*o.pressing > o.sensors)
            fail("--pressing " + *v + ": more than the " + std::to_string(o.sensors) + " simulated sensors");
    }
    o.timeout_s = o.virtual_clock || o.replay ? kSimulatedTimeoutSeconds : kLiveTimeoutSeconds;
    if (auto v = args.value("--timeout")) o.timeout_s = parse_seconds("--timeout", *v);
    if (auto v = args.value("--startup-timeout")) o.startup_timeout_s = parse_seconds("--startup-timeout", *v);
    publish_options(args, o);
    serve_option(args, o);
    capture_only_options(args, o);
    return o;
}

void adopt_remote(RunOptions& o, const Args& args, const IlluminationSequence& sequence, int background_frames,
                  int sensors) {
    o.sequence = sequence;
    o.background_frames = background_frames;
    o.sensors = sensors;
    if (!args.has("--object")) o.object = "live";  // a label only, as for real DIGITs
    background_options(args, o);  // the capture host's background decides whether skipping can be on
}

void adopt_recording(RunOptions& o, const Args& args, const Dataset& d) {
    if (d.sensors.empty()) fail(d.directory + ": the dataset has no sensors");
    if (d.run && !args.has("--sequence")) o.sequence = d.run->sequence;
    if (d.run) o.fusion = fusion_options(args, with_method(args, d.run->fusion));
    // A replay plays the windows as recorded: --window may only say so.
    const FusionWindow recorded = d.run ? d.run->window : FusionWindow::Cycle;
    if (args.has("--window") && o.window != recorded)
        fail("--window " + std::string(to_string(o.window)) + ": " + d.directory + " was recorded with " +
             std::string(to_string(recorded)) + " windows, and a replay plays them as recorded");
    o.window = recorded;
    const std::vector<std::string> objects = d.objects();
    if (!args.has("--object")) {
        if (objects.empty()) fail(d.directory + ": the dataset holds no object frames");
        o.object = objects.front();
    }
    o.sensors = int(d.sensors.size());
    o.background_frames = d.background_frames(o.sequence);
    background_options(args, o);  // the recording's background decides whether skipping can be on
}

}  // namespace vkfuse::cli

// vkfuse-bench --windows: what a sliding window buys (fused rate, latency from
// a contact change to the fused image) and what it costs (error), against the
// cycle it replaces. Each scene is one simulated DIGIT (QVGA, 60 fps, the
// paper's LED latency of 1.5 frames, camera locked) pressed by a coin that is
// still, taps or slides, captured by the rig's own Switcher on a virtual
// clock, once per window. A motion whose period is a whole number of cycles
// meets the schedule at one phase only, so each row is 2K runs of kSeconds,
// the press one frame later in each: every frame of a cycle (the K clean
// ones and the mixed ones between) sees a contact change. Every fused image is
// compared with the fusion it stands in for: each setting at one instant,
// i.e. every slot's frame rendered again (SimDigit::render) with its own
// noise and the contact of the window's newest frame. One plan fuses both,
// as two sensors, with one submit per window:
//
//   Switcher::next_cycle | next_window -> K frames (sensor 0)
//   SimDigit::render(index_k, setting_k, newest timestamp) -> K frames (sensor 1)
//   Plan::run -> fused 0 vs fused 1: max / mean abs error, metrics' relative error
#include "windows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/atomic_write.hpp"
#include "io/json_value.hpp"
#include "scatter_svg.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/rig/background.hpp"
#include "vkfuse/sensor/sim_digit.hpp"
#include "vkfuse/sensor/switching.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::bench {
namespace {

constexpr double kSeconds = 2.0;  // of sensor time per run: the slowest motion's period
constexpr int kBackgroundFrames = 20;
const char* const kSequences[] = {"15,15,15+0,15,0", "15,0,0+0,15,0+0,0,15"};

struct Scene {
    std::string name;
    SimMotion motion = SimMotion::Still;
    double period_s = 2.0;
};

struct Row {
    std::string scene, window, sequence;
    int frames = 0;
    double fused_fps = 0;               // fused images per second of sensor time
    double latency_mean_ms = NAN, latency_max_ms = NAN;  // contact change -> fused image; NaN: no change
    double max_abs_err = 0, mean_abs_err = 0;  // against the same-instant fusion
    double sharpness_rel_err = 0, contrast_rel_err = 0, background_diff_rel_err = 0;  // max over the images
    double span_max_ms = 0;  // the widest window
    int images = 0;
};

bool same_contact(const SimFrameTruth& a, const SimFrameTruth& b) {
    return a.object == b.object && a.contact_x == b.contact_x && a.contact_y == b.contact_y;
}

double rel_err(double a, double b) { return b == 0 ? std::abs(a) : std::abs(a - b) / std::abs(b); }

// The fused background: each setting's mean over frames with nothing pressed.
Image fused_background(Switcher& switcher, const IlluminationSequence& seq) {
    std::vector<ImageD> means;
    for (const Illumination& setting : seq) {
        const std::vector<Frame> frames = switcher.capture(setting, kBackgroundFrames);
        std::vector<FrameView> views;
        for (const Frame& f : frames) views.push_back(f.view());
        means.push_back(background_mean_reference(views));
    }
    return convert<float>(fuse_reference(means, FusionSpec{}));
}

// What the latencies need of each fused image: its newest frame.
struct Taken {
    double newest = 0;
    std::uint64_t newest_index = 0;
};

// One simulated DIGIT of the scene on a virtual clock of its own, nothing pressed.
struct Simulated {
    std::shared_ptr<Clock> clock = make_virtual_clock();
    std::unique_ptr<SimDigit> sim;
    explicit Simulated(const Scene& scene) {
        SimDigitOptions o;
        o.object = "nothing";  // still while calibrating and taking the background
        o.camera_auto = false;
        o.motion = scene.motion;
        o.motion_period_s = scene.period_s;
        o.clock = clock;
        sim = std::make_unique<SimDigit>(o);
    }
};

// What the runs of one row add up.
struct Tally {
    double abs_sum = 0;  // of each image's mean abs error
    double fps_sum = 0;
    int runs = 0;
    std::vector<double> latencies;
};

// One run: the coin pressed `phase` frames into the schedule, kSeconds of
// windows, each against the same instant's fusion.
void run_once(Plan& plan, const Scene& scene, const SwitchTiming& timing, FusionWindow window,
              const IlluminationSequence& seq, int phase, Row& row, Tally& tally) {
    Simulated s(scene);
    SimDigit& sim = *s.sim;
    Switcher switcher(sim, s.clock, timing);
    sim.set_object("coin");  // the motion starts now
    switcher.capture(seq.front(), 1 + phase);  // and the schedule `phase` frames later
    const double frame_span = sim.timing().frame_span_s(sim.timing().nominal_exposure_s);
    const int K = int(seq.size());
    std::vector<Taken> taken;
    double first = NAN;
    for (;;) {
        const std::vector<Frame> frames =
            window == FusionWindow::Sliding ? switcher.next_window(seq) : switcher.next_cycle(seq);
        Taken t{newest_timestamp(frames), 0};
        for (const Frame& f : frames)
            if (f.timestamp == t.newest) t.newest_index = f.index;
        if (std::isnan(first)) first = t.newest;
        if (t.newest - first > kSeconds) break;
        row.span_max_ms = std::max(row.span_max_ms, window_span(frames) * 1e3);
        std::vector<Frame> instant;
        for (int k = 0; k < K; ++k) instant.push_back(sim.render(frames[std::size_t(k)].index, seq[std::size_t(k)], t.newest));
        std::vector<FrameView> views;
        for (const Frame& f : frames) views.push_back(f.view());
        for (const Frame& f : instant) views.push_back(f.view());
        plan.run(views);
        const Image& a = plan.fused(0);
        const Image& b = plan.fused(1);
        double max_abs = 0, sum = 0;
        for (std::size_t i = 0; i < a.data.size(); ++i) {
            const double d = std::abs(double(a.data[i]) - double(b.data[i]));
            max_abs = std::max(max_abs, d);
            sum += d;
        }
        row.max_abs_err = std::max(row.max_abs_err, max_abs);
        tally.abs_sum += sum / double(a.data.size());
        const Metrics ma = plan.metrics(0), mb = plan.metrics(1);
        row.sharpness_rel_err = std::max(row.sharpness_rel_err, rel_err(ma.sharpness, mb.sharpness));
        row.contrast_rel_err = std::max(row.contrast_rel_err, rel_err(ma.contrast, mb.contrast));
        row.background_diff_rel_err =
            std::max(row.background_diff_rel_err, rel_err(*ma.background_diff, *mb.background_diff));
        taken.push_back(t);
    }
    row.images += int(taken.size());
    tally.fps_sum += double(taken.size() - 1) / (taken.back().newest - taken.front().newest);
    ++tally.runs;
    // A contact change: the first frame showing a contact its predecessor did
    // not. Its latency runs from that frame's start to the end of the newest
    // frame of the first image fused with it (or a later frame) in it.
    const std::uint64_t from = taken.front().newest_index + 1, to = taken.back().newest_index;
    std::size_t w = 0;
    for (std::uint64_t n = from; n <= to; ++n) {
        const SimFrameTruth now = sim.truth(n), before = sim.truth(n - 1);
        if (same_contact(now, before)) continue;
        while (w < taken.size() && taken[w].newest_index < n) ++w;
        if (w == taken.size()) break;
        tally.latencies.push_back(taken[w].newest + frame_span - now.timestamp);
    }
}

Row run_scene(Context& ctx, const Scene& scene, FusionWindow window, const IlluminationSequence& seq,
              const std::string& sequence_text, int phases) {
    // Calibrated and background taken once: every run's sensor is the same.
    Simulated first(scene);
    const SwitchTiming timing = measure_switch_timing(*first.sim, *first.clock);
    Switcher switcher(*first.sim, first.clock, timing);
    const Image background = fused_background(switcher, seq);
    PlanConfig cfg;
    cfg.height = first.sim->info().height;
    cfg.width = first.sim->info().width;
    cfg.frames = int(seq.size());
    cfg.sensors = 2;  // the window's frames, and the same instant's
    cfg.input = PixelType::U8;
    cfg.metrics = MetricSet::all();
    Plan plan(ctx, cfg);
    for (int s = 0; s < 2; ++s) plan.set_background(s, FrameView::of(background));

    Row row{scene.name, std::string(to_string(window)), sequence_text, int(seq.size())};
    Tally tally;
    for (int phase = 0; phase < phases; ++phase) run_once(plan, scene, timing, window, seq, phase, row, tally);
    row.mean_abs_err = tally.abs_sum / double(row.images);
    row.fused_fps = tally.fps_sum / double(tally.runs);
    if (!tally.latencies.empty()) {
        row.latency_max_ms = *std::max_element(tally.latencies.begin(), tally.latencies.end()) * 1e3;
        double sum = 0;
        for (double l : tally.latencies) sum += l;
        row.latency_mean_ms = sum / double(tally.latencies.size()) * 1e3;
    }
    return row;
}

json::Value number_or_null(double v) { return std::isnan(v) ? json::Value(nullptr) : json::Value(v); }

json::Value row_json(const Row& r) {
    json::Value::Object o;
    o.emplace_back("scene", json::Value(r.scene));
    o.emplace_back("window", json::Value(r.window));
    o.emplace_back("sequence", json::Value(r.sequence));
    o.emplace_back("frames", json::Value(r.frames));
    o.emplace_back("images", json::Value(r.images));
    o.emplace_back("fused_fps", json::Value(r.fused_fps));
    o.emplace_back("latency_mean_ms", number_or_null(r.latency_mean_ms));
    o.emplace_back("latency_max_ms", number_or_null(r.latency_max_ms));
    o.emplace_back("span_max_ms", json::Value(r.span_max_ms));
    o.emplace_back("max_abs_err", json::Value(r.max_abs_err));
    o.emplace_back("mean_abs_err", json::Value(r.mean_abs_err));
    o.emplace_back("sharpness_rel_err", json::Value(r.sharpness_rel_err));
    o.emplace_back("contrast_rel_err", json::Value(r.contrast_rel_err));
    o.emplace_back("background_diff_rel_err", json::Value(r.background_diff_rel_err));
    return json::Value(std::move(o));
}

std::string latency_text(double ms) {
    if (std::isnan(ms)) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", ms);
    return text;
}

}  // namespace

int run_windows(const Options& o) {
    // --quick: the fastest motions, K = 2, two phases (the ctest's check).
    const bool quick = o.scope == Scope::Quick;
    std::vector<Scene> scenes = {{"still", SimMotion::Still, 2.0},  {"tap 0.5s", SimMotion::Tap, 0.5},
                                 {"slide 0.5s", SimMotion::Slide, 0.5}};
    if (!quick)
        scenes.insert(scenes.end(), {{"tap 1s", SimMotion::Tap, 1.0},
                                     {"tap 2s", SimMotion::Tap, 2.0},
                                     {"slide 1s", SimMotion::Slide, 1.0},
                                     {"slide 2s", SimMotion::Slide, 2.0}});
    std::vector<int> ks = o.frames;
    if (ks.empty()) ks = quick ? std::vector<int>{2} : std::vector<int>{2, 3};
    ContextOptions co;
    co.device_index = o.device;
    Context ctx(co);
    std::printf("vkfuse-bench --windows: %s, simulated DIGIT (QVGA, 60 fps, LED latency 1.5 frames), coin, "
                "wavelet bior4.4 L3, %s runs of %.0f s of sensor time per row; error against fusing every setting at one "
                "instant\n",
                ctx.device().name.c_str(), quick ? "2" : "2K", kSeconds);
    std::printf("%-10s %-7s %2s %7s %9s %9s %8s %10s %10s %9s %9s %9s\n", "scene", "window", "K", "fps", "lat_mean",
                "lat_max", "span_ms", "max_abs", "mean_abs", "sharp_re", "contr_re", "bgdiff_re");
    std::vector<Row> rows;
    for (const char* sequence_text : kSequences) {
        const IlluminationSequence seq = parse_sequence(sequence_text);
        if (std::find(ks.begin(), ks.end(), int(seq.size())) == ks.end()) continue;
        const int phases = quick ? 2 : 2 * int(seq.size());
        for (const Scene& scene : scenes)
            for (FusionWindow window : {FusionWindow::Cycle, FusionWindow::Sliding}) {
                const Row r = run_scene(ctx, scene, window, seq, sequence_text, phases);
                std::printf("%-10s %-7s %2d %7.2f %9s %9s %8.1f %10.3g %10.3g %9.3g %9.3g %9.3g\n", r.scene.c_str(),
                            r.window.c_str(), r.frames, r.fused_fps, latency_text(r.latency_mean_ms).c_str(),
                            latency_text(r.latency_max_ms).c_str(), r.span_max_ms, r.max_abs_err, r.mean_abs_err,
                            r.sharpness_rel_err, r.contrast_rel_err, r.background_diff_rel_err);
                std::fflush(stdout);
                rows.push_back(r);
            }
    }
    if (!o.json_path.empty()) {
        json::Value::Array a;
        for (const Row& r : rows) a.push_back(row_json(r));
        const std::string text = json::write(json::Value(std::move(a))) + "\n";
        io::write_atomically(o.json_path, [&](std::FILE* f) { io::write_all(f, text, o.json_path); });
    }
    if (!o.plot_path.empty()) {
        std::vector<ScatterPoint> points;
        for (const Row& r : rows)
            points.push_back({r.mean_abs_err, r.fused_fps, r.window + " K=" + std::to_string(r.frames),
                              r.scene + ", " + r.window + ", K=" + std::to_string(r.frames)});
        write_scatter_svg(o.plot_path, points,
                          {"vkfuse-bench --windows on " + ctx.device().name + ": fused rate against error",
                           "mean abs error against every setting at one instant", "fused images / s"});
    }
    return 0;
}

}  // namespace vkfuse::bench

// vkfuse-bench --scenes: what skipping buys on simulated scenes, against its
// error (include/vkfuse/core/skip.hpp). Each scene is a sequence of cycles a
// simulated DIGIT delivers (QVGA, K = 3, no LED latency to wait out: the
// fusion is timed, not the capture); every skip setting runs the same
// frames through its own plan, and a plan that skips nothing gives the full
// fusion each one is compared with.
#include "scenes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/sparse_wavelet.hpp"
#include "io/atomic_write.hpp"
#include "io/json_value.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/rig/background.hpp"
#include "vkfuse/sensor/sim_digit.hpp"
#include "vkfuse/vk/plan.hpp"
#include "scatter_svg.hpp"

namespace vkfuse::bench {
namespace {

constexpr int kCycles = 24, kBackgroundFrames = 20;
const char* const kSequence = "15,15,15+0,15,0+15,0,0";

struct Scene {
    std::string name;
    std::string object;  // "nothing": no contact
    double depth_mm = 1.0;
    SimMotion motion = SimMotion::Still;
};

using Frames = std::vector<std::vector<std::uint8_t>>;  // K frames of a cycle

// The next frame lit wholly by `setting` (the simulator knows which are).
std::vector<std::uint8_t> lit_frame(SimDigit& sim, const Illumination& setting) {
    for (int tries = 0; tries < 16; ++tries) {
        const Frame f = sim.grab();
        const SimFrameTruth t = sim.truth(f.index);
        if (!t.mixed && t.lit_by == setting) return f.pixels;
    }
    throw Error(ErrorKind::Device, "--scenes: the simulator gave no frame lit by " + setting.to_string());
}

struct SceneData {
    SkipReference reference;
    Image background;  // the means fused: what background_diff compares with
    std::vector<Frames> cycles;
};

SceneData capture(const Scene& scene, const IlluminationSequence& sequence) {
    SimDigitOptions o;
    o.object = "nothing";
    o.camera_auto = false;
    o.motion = scene.motion;
    o.motion_period_s = kCycles * double(sequence.size()) * 2 / 60.0;  // one slide over the scene
    SimDigit sim(o);
    const int H = sim.info().height, W = sim.info().width;
    SceneData d;
    std::vector<ImageD> means;
    for (const Illumination& setting : sequence) {
        sim.set_illumination(setting);
        std::vector<std::vector<std::uint8_t>> frames;
        std::vector<FrameView> views;
        for (int n = 0; n < kBackgroundFrames; ++n) frames.push_back(lit_frame(sim, setting));
        for (const auto& f : frames) views.push_back({f.data(), H, W, 3, PixelType::U8});
        const Image mean = convert<float>(background_mean_reference(views));
        d.reference.deviation.push_back(background_deviation(views, mean));
        d.reference.mean.push_back(mean);
        means.push_back(convert<double>(mean));
    }
    d.background = convert<float>(fuse_reference(means, FusionSpec{}));
    sim.set_object(scene.object, scene.depth_mm);
    for (int c = 0; c < kCycles; ++c) {
        Frames cycle;
        for (const Illumination& setting : sequence) {
            sim.set_illumination(setting);
            cycle.push_back(lit_frame(sim, setting));
        }
        d.cycles.push_back(std::move(cycle));
    }
    return d;
}

struct Outcome {
    std::vector<double> ms;
    double fused_fraction = 0, changed_fraction = 0;
    std::vector<Image> fused;  // per cycle, from the first pass
    std::vector<SkipRegion> regions;  // per cycle: what was fused (empty: idle or reused)
    double median_ms() {
        std::sort(ms.begin(), ms.end());
        return ms[ms.size() / 2];
    }
};

Plan make_plan(Context& ctx, const SceneData& d, SkipConfig skip) {
    const Image& first = d.reference.mean.front();
    PlanConfig cfg;
    cfg.height = first.height;
    cfg.width = first.width;
    cfg.frames = int(d.reference.mean.size());
    cfg.input = PixelType::U8;
    cfg.metrics = MetricSet::all();
    cfg.skip = skip;
    Plan plan(ctx, cfg);
    plan.set_background(0, FrameView::of(d.background));
    if (skip.policy != SkipPolicy::Off) plan.set_skip_reference(0, d.reference);
    return plan;
}

// Every setting's plan runs each cycle in turn (round robin), so that a
// busy moment of the host falls on all of them alike.
std::vector<Outcome> run_plans(Context& ctx, const SceneData& d, const std::vector<SkipConfig>& skips, int runs) {
    std::vector<Plan> plans;
    for (const SkipConfig& s : skips) plans.push_back(make_plan(ctx, d, s));
    std::vector<Outcome> out(plans.size());
    const Image& first = d.reference.mean.front();
    for (int r = 0; r < runs; ++r)
        for (const Frames& cycle : d.cycles) {
            std::vector<FrameView> views;
            for (const auto& f : cycle) views.push_back({f.data(), first.height, first.width, 3, PixelType::U8});
            for (std::size_t p = 0; p < plans.size(); ++p) {
                const auto start = std::chrono::steady_clock::now();
                plans[p].run(views);
                const Image& fused = plans[p].fused(0);
                plans[p].metrics(0);
                out[p].ms.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
                if (r > 0) continue;
                out[p].fused.push_back(fused);
                const SkipOutcome o = plans[p].skip_outcome(0);
                out[p].regions.push_back(o.fused_region);
                out[p].fused_fraction += o.fused_fraction / double(d.cycles.size());
                out[p].changed_fraction += o.changed_fraction / double(d.cycles.size());
            }
        }
    return out;
}

// The transform work `--skip tiles` does on one cycle, as a share of full
// fusion's (core/sparse_wavelet.hpp's model): the changed tiles' rectangle
// grown by the wavelet's reach, 1 where it fuses whole, 0 with no changed tile.
double tiles_work(const SceneData& d, const Frames& cycle) {
    const Image& first = d.reference.mean.front();
    const int H = first.height, W = first.width;
    std::vector<FrameView> views;
    for (const auto& f : cycle) views.push_back({f.data(), H, W, 3, PixelType::U8});
    std::vector<bool> changed;
    for (double score : change_scores_reference(views, d.reference)) changed.push_back(score > SkipConfig{}.threshold);
    if (std::none_of(changed.begin(), changed.end(), [](bool c) { return c; })) return 0;
    const int K = int(cycle.size());
    const auto choice = core::choose_sparse(FusionSpec{}, H, W, K, 3, changed, skip_tiles_x(W));
    return choice ? choice->plan.work_fraction(K, 3) : 1.0;
}

// The largest |a - b| inside the region fused and outside it.
struct Errors {
    double inside = 0, outside = 0;
};
Errors max_abs(const Image& a, const Image& b, const SkipRegion& fused) {
    Errors e;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double& err = fused.contains(y, x, a.height, a.width) ? e.inside : e.outside;
            for (int c = 0; c < a.channels; ++c) err = std::max(err, std::abs(double(a.at(y, x, c)) - double(b.at(y, x, c))));
        }
    return e;
}

struct Row {
    std::string scene, skip;
    double threshold = 0, contact_fraction = 0, fused_fraction = 1, median_ms = 0, full_median_ms = 0;
    double max_abs_err_contact = 0, max_abs_err_outside = 0;
    double tiles_work_fraction = 0;  // the scene's, from the tile-sparse work model
};

json::Value row_json(const Row& r) {
    json::Value::Object o;
    o.emplace_back("scene", json::Value(r.scene));
    o.emplace_back("skip", json::Value(r.skip));
    o.emplace_back("threshold", r.skip == "off" ? json::Value(nullptr) : json::Value(r.threshold));
    o.emplace_back("contact_fraction", json::Value(r.contact_fraction));
    o.emplace_back("fused_fraction", json::Value(r.fused_fraction));
    o.emplace_back("median_ms", json::Value(r.median_ms));
    o.emplace_back("full_median_ms", json::Value(r.full_median_ms));
    o.emplace_back("time_fraction", json::Value(r.median_ms / r.full_median_ms));
    o.emplace_back("max_abs_err_contact", json::Value(r.max_abs_err_contact));
    o.emplace_back("max_abs_err_outside", json::Value(r.max_abs_err_outside));
    o.emplace_back("tiles_work_fraction", json::Value(r.tiles_work_fraction));
    return json::Value(std::move(o));
}

// Time (share of full fusion) against the error outside the fused cycles,
// one colour per scene.
void write_plot(const std::string& path, const std::vector<Row>& rows, const std::string& device) {
    std::vector<ScatterPoint> points;
    for (const Row& r : rows)
        points.push_back({r.max_abs_err_outside, r.median_ms / r.full_median_ms, r.scene,
                          r.scene + " " + r.skip + " " + (r.skip == "off" ? "" : std::to_string(int(r.threshold)))});
    write_scatter_svg(path, points,
                      {"vkfuse-bench --scenes on " + device + ": time against error",
                       "max abs error outside fused cycles", "time / full"});
}

}  // namespace

int run_scenes(const Options& o) {
    // The simulator's objects all span much of the gel at the usual 1 mm:
    // a ball pressed lightly is the small contact.
    const std::vector<Scene> scenes = {{"none", "nothing", 1.0, SimMotion::Still},
                                       {"small", "ball", 0.1, SimMotion::Still},
                                       {"ball", "ball", 0.3, SimMotion::Still},
                                       {"coin", "coin-heads", 1.0, SimMotion::Still},
                                       {"slide", "ball", 0.3, SimMotion::Slide}};
    const std::vector<double> thresholds = {4, SkipConfig{}.threshold, 16};
    const IlluminationSequence sequence = parse_sequence(kSequence);
    ContextOptions co;
    co.device_index = o.device;
    Context ctx(co);
    const int runs = std::max(1, o.runs / kCycles + 1);
    std::printf("vkfuse-bench --scenes: %s, QVGA, K=3 (%s), wavelet bior4.4 L3, %d cycles per scene x %d\n",
                ctx.device().name.c_str(), kSequence, kCycles, runs);
    std::printf("%-6s %-6s %9s %8s %7s %10s %10s %8s %12s %12s\n", "scene", "skip", "threshold", "contact", "fused",
                "median_ms", "full_ms", "time", "err_contact", "err_outside");
    std::vector<Row> rows;
    for (const Scene& scene : scenes) {
        const SceneData d = capture(scene, sequence);
        std::vector<SkipConfig> skips = {SkipConfig{}};
        for (SkipPolicy p : {SkipPolicy::Idle, SkipPolicy::Static, SkipPolicy::Tiles})
            for (double t : thresholds) skips.push_back({p, t});
        std::vector<Outcome> outs = run_plans(ctx, d, skips, runs);
        const double full_ms = outs[0].median_ms();
        // The share of tiles the contact changes, as the default threshold sees it.
        const auto at_default = std::find_if(skips.begin(), skips.end(), [](const SkipConfig& s) {
            return s.policy == SkipPolicy::Idle && s.threshold == SkipConfig{}.threshold;
        });
        const double contact = outs[std::size_t(at_default - skips.begin())].changed_fraction;
        double tiles = 0;
        for (const Frames& cycle : d.cycles) tiles += tiles_work(d, cycle) / double(d.cycles.size());
        for (std::size_t p = 0; p < skips.size(); ++p) {
            Outcome& out = outs[p];
            const bool off = skips[p].policy == SkipPolicy::Off;
            Row r{scene.name, std::string(to_string(skips[p].policy)), skips[p].threshold, contact,
                  off ? 1.0 : out.fused_fraction, out.median_ms(), full_ms, 0, 0, tiles};
            for (std::size_t c = 0; c < d.cycles.size(); ++c) {
                const Errors e = max_abs(out.fused[c], outs[0].fused[c], out.regions[c]);
                r.max_abs_err_contact = std::max(r.max_abs_err_contact, e.inside);
                r.max_abs_err_outside = std::max(r.max_abs_err_outside, e.outside);
            }
            std::printf("%-6s %-6s %9s %8.3f %7.3f %10.3f %10.3f %7.1f%% %12.3g %12.3g\n", r.scene.c_str(),
                        r.skip.c_str(), off ? "-" : std::to_string(int(r.threshold)).c_str(), r.contact_fraction,
                        r.fused_fraction, r.median_ms, r.full_median_ms, 100 * r.median_ms / r.full_median_ms,
                        r.max_abs_err_contact, r.max_abs_err_outside);
            std::fflush(stdout);
            rows.push_back(r);
        }
        std::printf("%-6s tile-sparse model: %.1f%% of full fusion's transform work (changed tiles + wavelet reach)\n",
                    scene.name.c_str(), 100 * tiles);
    }
    if (!o.json_path.empty()) {
        json::Value::Array a;
        for (const Row& r : rows) a.push_back(row_json(r));
        const std::string text = json::write(json::Value(std::move(a))) + "\n";
        io::write_atomically(o.json_path, [&](std::FILE* f) { io::write_all(f, text, o.json_path); });
    }
    if (!o.plot_path.empty()) write_plot(o.plot_path, rows, ctx.device().name);
    return 0;
}

}  // namespace vkfuse::bench

// vkfuse_soak: Plan::run over and over, as a rig would run for days, watching
// for what a short test cannot see: resident memory creeping up, results
// changing for the same input, Vulkan objects left behind. Not a unit test
// (it runs for minutes); .ci/run starts it.
//
//   vkfuse_soak [--cycles N] [--width W] [--height H] [--check-every N] [--warmup N]
//
// Two sensors' worth of frames alternate (A, B, A, ...): every check-every
// cycles the fused image and metrics must equal, bit for bit, those of the
// first cycle that saw the same input. Resident memory (/proc/self/statm) is
// recorded after the warm-up and ten times more. A leak grows with every
// cycle; a driver's pools fill to a steady size and stop (lavapipe, Mesa 25,
// with descriptor-bound kernels: about 6 MiB over the first 6000 cycles, then
// flat). So over the last 40 % of the run memory may grow by less than 1 MiB,
// and from the warm-up to the end by less than 16 MiB. The validation layer is on throughout: its
// object tracker reports every object still alive at vkDestroyDevice /
// vkDestroyInstance, and any validation message fails the run. Prints the RSS
// curve and one JSON line; exit status 0 when everything held, 1 otherwise.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include "vkfuse/core/error.hpp"
#include "vkfuse/vk/context.hpp"
#include "vkfuse/vk/plan.hpp"

namespace {

struct Options {
    long cycles = 100000;
    int width = 320, height = 240;  // QVGA, the DIGIT's frame
    long check_every = 1000;
    long warmup = 1000;
};

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr,
                 "vkfuse_soak: %s\nusage: vkfuse_soak [--cycles N] [--width W] [--height H] [--check-every N] "
                 "[--warmup N]\n",
                 problem.c_str());
    std::exit(2);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string name = argv[i];
        if (i + 1 == argc) usage("option " + name + " needs a value");
        char* end = nullptr;
        const long value = std::strtol(argv[++i], &end, 10);
        if (*end != '\0' || value < 1) usage(name + " " + argv[i] + ": expected a positive integer");
        if (name == "--cycles") o.cycles = value;
        else if (name == "--width") o.width = int(value);
        else if (name == "--height") o.height = int(value);
        else if (name == "--check-every") o.check_every = value;
        else if (name == "--warmup") o.warmup = value;
        else usage("unknown option " + name);
    }
    if (o.warmup >= o.cycles) usage("--warmup must be below --cycles");
    return o;
}

// Resident set size in bytes: statm's second field counts pages.
long resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    long size = 0, resident = 0;
    statm >> size >> resident;
    return resident * sysconf(_SC_PAGESIZE);
}

double mib(long bytes) { return double(bytes) / (1024.0 * 1024.0); }

// A camera-like 8-bit frame: smooth shading, an edge, and per-frame texture.
std::vector<std::uint8_t> frame(int h, int w, int k) {
    std::vector<std::uint8_t> px(std::size_t(h) * w * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const double v = 90 + 60 * std::sin(0.05 * x + c + k) * std::cos(0.07 * y) + (x > w / 2 ? 40 : 0) +
                                 ((x * 7 + y * 13 + k * 31) % 17);
                px[(std::size_t(y) * w + x) * 3 + c] = std::uint8_t(std::clamp(v, 0.0, 255.0));
            }
    return px;
}

struct Result {
    std::vector<float> fused;
    vkfuse::Metrics metrics;
};

bool same(const Result& a, const vkfuse::Image& fused, const vkfuse::Metrics& m) {
    return std::memcmp(a.fused.data(), fused.data.data(), a.fused.size() * sizeof(float)) == 0 &&
           a.metrics.sharpness == m.sharpness && a.metrics.contrast == m.contrast;
}

struct Validation {
    std::mutex mutex;
    std::vector<std::string> messages;
};

int soak(const Options& o) {
    Validation validation;  // outlives the context: leak reports come at its destruction
    const long rss_start = resident_bytes();
    std::vector<std::pair<long, long>> curve;  // (cycle, resident bytes)
    long mismatches = 0;
    double seconds = 0;
    {
        vkfuse::ContextOptions options;
        options.validation = true;
        options.on_validation_message = [&](const std::string& m) {
            std::lock_guard lock(validation.mutex);
            validation.messages.push_back(m);
        };
        vkfuse::Context context(options);
        vkfuse::PlanConfig cfg;  // wavelet, bior4.4, mean / max-abs
        // 3 levels (the default) where the frame carries them, else as many as it does.
        cfg.fusion.levels = std::min(3, vkfuse::max_wavelet_levels(cfg.fusion.wavelet, o.height, o.width));
        cfg.height = o.height;
        cfg.width = o.width;
        cfg.channels = 3;
        cfg.frames = 2;
        cfg.sensors = 1;
        cfg.input = vkfuse::PixelType::U8;
        vkfuse::Plan plan(context, cfg);
        const std::vector<std::vector<std::uint8_t>> frames{frame(o.height, o.width, 0), frame(o.height, o.width, 1),
                                                            frame(o.height, o.width, 2), frame(o.height, o.width, 3)};
        std::vector<std::vector<vkfuse::FrameView>> inputs(2);
        for (int i = 0; i < 4; ++i)
            inputs[std::size_t(i / 2)].push_back({frames[std::size_t(i)].data(), o.height, o.width, 3, vkfuse::PixelType::U8});
        std::vector<Result> first(2);
        const long curve_step = std::max(1L, (o.cycles - o.warmup) / 10);
        std::printf("vkfuse_soak: %ld cycles of %dx%dx3, K=2, wavelet bior4.4 L=%d with metrics, on %s\n", o.cycles,
                    o.width, o.height, cfg.fusion.levels, context.device().name.c_str());
        curve.emplace_back(0, resident_bytes());
        const auto start = std::chrono::steady_clock::now();
        for (long cycle = 0; cycle < o.cycles; ++cycle) {
            const std::size_t input = std::size_t(cycle % 2);
            plan.run(inputs[input]);
            const vkfuse::Image& fused = plan.fused(0);  // read back every cycle, as a rig does
            const vkfuse::Metrics m = plan.metrics(0);
            if (cycle < 2) {
                first[input] = {fused.data, m};
            } else if (cycle % o.check_every < 2 || cycle >= o.cycles - 2) {
                if (!same(first[input], fused, m)) {
                    ++mismatches;
                    std::printf("cycle %ld: output differs from cycle %zu's for the same input\n", cycle, input);
                }
            }
            if (cycle + 1 == o.warmup || (cycle + 1 > o.warmup && (cycle + 1 - o.warmup) % curve_step == 0) ||
                cycle + 1 == o.cycles)
                curve.emplace_back(cycle + 1, resident_bytes());
        }
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }  // plan, then context: the validation layer reports leaked objects here
    const long rss_warm = curve[1].second, rss_end = curve.back().second;
    const long growth = rss_end - rss_warm;
    // The first sample at or after 60 % of the cycles.
    long rss_late = rss_end;
    for (const auto& [cycle, bytes] : curve)
        if (cycle * 10 >= o.cycles * 6) {
            rss_late = bytes;
            break;
        }
    const long late_growth = rss_end - rss_late;
    std::printf("resident memory (MiB): start %.2f", mib(rss_start));
    for (const auto& [cycle, bytes] : curve) std::printf(", %ld: %.2f", cycle, mib(bytes));
    std::printf("\n");
    std::printf("%.1f s, %.3f ms per cycle; growth after warm-up %+.3f MiB, over the last 40 %% %+.3f MiB; %ld "
                "mismatches; %zu validation messages\n",
                seconds, 1000 * seconds / double(o.cycles), mib(growth), mib(late_growth), mismatches,
                validation.messages.size());
    for (const std::string& m : validation.messages) std::printf("validation: %s\n", m.c_str());
    const bool ok = late_growth < 1024 * 1024 && growth < 16 * 1024 * 1024 && mismatches == 0 &&
                    validation.messages.empty();
    std::printf(
        "{\"cycles\": %ld, \"width\": %d, \"height\": %d, \"seconds\": %.1f, \"rss_start_mib\": %.2f, "
        "\"rss_after_warmup_mib\": %.2f, \"rss_end_mib\": %.2f, \"mismatches\": %ld, \"validation_messages\": %zu, "
        "\"ok\": %s}\n",
        o.cycles, o.width, o.height, seconds, mib(rss_start), mib(rss_warm), mib(rss_end), mismatches,
        validation.messages.size(), ok ? "true" : "false");
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return soak(parse(argc, argv));
    } catch (const vkfuse::Error& e) {
        std::fprintf(stderr, "vkfuse_soak: %s\n", e.what());
        return 2;
    }
}

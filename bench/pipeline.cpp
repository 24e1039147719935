// vkfuse-bench --pipeline: what a second cycle in flight buys a sensor loop.
// The loop is the rig's: S sensors' 8-bit frames up, every sensor's fused
// image and metrics read back. As a round trip each cycle is Plan::run then
// the reads; with two cycles in flight it is submit(c + 1), collect(c), then
// c's reads while c + 1 runs on the device:
//
//   round trip   host  up c | wait ...... | read c | up c+1 | wait ....
//                dev         | fuse c     |        |        | fuse c+1
//   in flight    host  up c+1 | wait | read c | up c+2 | wait | read c+1
//                dev   fuse c ......| fuse c+1 .....| fuse c+2 ...
//
// Both plans run in alternating blocks of cycles, so that a busy moment of
// the host falls on both alike, and every result of the pipelined plan is
// compared with the round trip's (the same kernels on the same frames: they
// must agree to the bit).
#include "pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "inputs.hpp"
#include "io/atomic_write.hpp"
#include "io/json_value.hpp"
#include "result.hpp"
#include "timing.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::bench {
namespace {

constexpr int kDefaultSensors = 16, kBlocks = 5;

struct Row {
    Cell cell;
    int in_flight = 1;
    double median_ms = 0;      // per cycle of all sensors, median over the blocks
    double round_trip_ms = 0;  // the same for the round trip
    double max_abs_diff = 0;   // against the round trip's results
};

// The workload's frames as a rig delivers them: 8 bits per sample.
struct Frames8 {
    std::vector<std::vector<std::uint8_t>> data;
    std::vector<FrameView> views;
};
Frames8 to_u8(const Inputs& in) {
    Frames8 f;
    for (int s = 0; s < in.sensors(); ++s)
        for (int k = 0; k < in.frames(); ++k) {
            const Image& img = in.frame(s, k);
            std::vector<std::uint8_t> bytes(img.data.size());
            for (std::size_t i = 0; i < bytes.size(); ++i)
                bytes[i] = std::uint8_t(std::lround(std::clamp(double(img.data[i]), 0.0, 1.0) * 255));
            f.data.push_back(std::move(bytes));
        }
    for (std::size_t i = 0; i < f.data.size(); ++i)
        f.views.push_back({f.data[i].data(), in.size().height, in.size().width, 3, PixelType::U8});
    return f;
}

Plan make_plan(Context& ctx, const Cell& cell, const Inputs& in, int in_flight) {
    PlanConfig cfg;
    cfg.fusion = cell.fusion();
    cfg.height = cell.size.height;
    cfg.width = cell.size.width;
    cfg.frames = cell.frames;
    cfg.sensors = cell.sensors;
    cfg.input = PixelType::U8;
    cfg.metrics = MetricSet::all();
    cfg.cycles_in_flight = in_flight;
    Plan plan(ctx, cfg);
    for (int s = 0; s < cell.sensors; ++s) plan.set_background(s, FrameView::of(in.background(s)));
    return plan;
}

// Every sensor's results, read as the rig reads them.
void read_all(const Plan& plan) {
    for (int s = 0; s < plan.config().sensors; ++s) {
        plan.fused(s);
        plan.metrics(s);
    }
}

double largest_difference(const Plan& a, const Plan& b) {
    double d = 0;
    for (int s = 0; s < a.config().sensors; ++s) {
        const Image &x = a.fused(s), &y = b.fused(s);
        for (std::size_t i = 0; i < x.data.size(); ++i) d = std::max(d, std::abs(double(x.data[i]) - double(y.data[i])));
        const Metrics mx = a.metrics(s), my = b.metrics(s);
        d = std::max({d, std::abs(mx.sharpness - my.sharpness), std::abs(mx.contrast - my.contrast),
                      std::abs(mx.background_diff.value_or(0) - my.background_diff.value_or(0))});
    }
    return d;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Row measure(Context& ctx, const Cell& cell, const Options& o) {
    const Inputs in(cell.size, cell.frames, cell.sensors);
    const Frames8 frames = to_u8(in);
    Plan round_trip = make_plan(ctx, cell, in, 1), pipelined = make_plan(ctx, cell, in, 2);
    const int cycles = std::max(2, o.runs);
    for (int w = 0; w < std::max(1, o.warmup); ++w) {
        round_trip.run(frames.views);
        pipelined.run(frames.views);
    }
    Row row{cell, 2};
    row.max_abs_diff = largest_difference(round_trip, pipelined);
    std::vector<double> rt_ms, pipe_ms;
    for (int b = 0; b < kBlocks; ++b) {
        auto start = std::chrono::steady_clock::now();
        for (int c = 0; c < cycles; ++c) {
            round_trip.run(frames.views);
            read_all(round_trip);
        }
        rt_ms.push_back(ms_since(start) / cycles);
        pipelined.submit(frames.views);  // the first cycle of the block, collected in its first step
        start = std::chrono::steady_clock::now();
        for (int c = 0; c < cycles; ++c) {
            pipelined.submit(frames.views);
            pipelined.collect();
            read_all(pipelined);
        }
        pipe_ms.push_back(ms_since(start) / cycles);
        pipelined.collect();  // the block's last cycle, outside its time
        row.max_abs_diff = std::max(row.max_abs_diff, largest_difference(round_trip, pipelined));
    }
    row.median_ms = median(pipe_ms);
    row.round_trip_ms = median(rt_ms);
    return row;
}

json::Value row_json(const Row& r, const std::string& device, int in_flight, double ms) {
    json::Value::Object o;
    o.emplace_back("method", json::Value(label(r.cell.method)));
    o.emplace_back("levels", json::Value(double(r.cell.levels)));
    o.emplace_back("device", json::Value(device));
    o.emplace_back("width", json::Value(double(r.cell.size.width)));
    o.emplace_back("height", json::Value(double(r.cell.size.height)));
    o.emplace_back("frames", json::Value(double(r.cell.frames)));
    o.emplace_back("sensors", json::Value(double(r.cell.sensors)));
    o.emplace_back("cycles_in_flight", json::Value(double(in_flight)));
    o.emplace_back("median_ms", json::Value(ms));
    o.emplace_back("throughput_cycles_s", json::Value(1000.0 * r.cell.sensors / ms));
    o.emplace_back("speedup", json::Value(r.round_trip_ms / ms));
    o.emplace_back("max_abs_diff", json::Value(in_flight == 1 ? 0.0 : r.max_abs_diff));
    return json::Value(std::move(o));
}

}  // namespace

int run_pipeline(const Options& o) {
    std::vector<MethodVariant> methods;
    if (o.methods.empty()) {
        methods = batched_methods();
    } else {
        for (Method m : o.methods) {
            if (o.wavelets.empty() || !MethodVariant{m}.has_wavelet())
                methods.push_back({m});
            else
                for (Wavelet w : o.wavelets) methods.push_back({m, w});
        }
    }
    const Size size = o.sizes.empty() ? Size{320, 240} : o.sizes.front();
    const int K = o.frames.empty() ? 3 : o.frames.front();
    const int S = o.sensors.empty() ? kDefaultSensors : o.sensors.front();
    ContextOptions co;
    co.device_index = o.device;
    Context ctx(co);
    std::printf("vkfuse-bench --pipeline: %s, %s, K=%d, S=%d, 8-bit frames, every fused image and metric read "
                "back; %d blocks of %d cycles each way\n",
                ctx.device().name.c_str(), short_size_name(size).c_str(), K, S, kBlocks, std::max(2, o.runs));
    std::printf("%-18s %11s %14s %11s %14s %8s %12s\n", "method", "round_ms", "round_cyc/s", "flight2_ms",
                "flight2_cyc/s", "speedup", "max_abs_diff");
    json::Value::Array rows;
    bool identical = true;
    for (const MethodVariant& m : methods) {
        FusionSpec spec;
        spec.method = m.method;
        spec.wavelet = m.wavelet;
        const Cell cell{m, spec.effective_levels(), Backend::Vulkan, Precision::Fp32, size, K, S, ""};
        const Row r = measure(ctx, cell, o);
        std::printf("%-18s %11.3f %14.1f %11.3f %14.1f %7.2fx %12.3g\n", label(m).c_str(), r.round_trip_ms,
                    1000.0 * S / r.round_trip_ms, r.median_ms, 1000.0 * S / r.median_ms, r.round_trip_ms / r.median_ms,
                    r.max_abs_diff);
        std::fflush(stdout);
        identical = identical && r.max_abs_diff == 0;
        rows.push_back(row_json(r, ctx.device().name, 1, r.round_trip_ms));
        rows.push_back(row_json(r, ctx.device().name, 2, r.median_ms));
    }
    if (!o.json_path.empty()) {
        const std::string text = json::write(json::Value(std::move(rows))) + "\n";
        io::write_atomically(o.json_path, [&](std::FILE* f) { io::write_all(f, text, o.json_path); });
    }
    if (!identical) std::fprintf(stderr, "vkfuse-bench --pipeline: two cycles in flight changed a result\n");
    return identical ? 0 : 1;
}

}  // namespace vkfuse::bench

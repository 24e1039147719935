// The emulated DIGIT's camera (renderer.hpp).
#include "renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "sensor/frame_codec.hpp"

namespace vkfuse::emulator {
namespace {

SimDigitOptions sim_options(const RendererOptions& o, bool vga) {
    SimDigitOptions s;
    s.vga = vga;
    s.object = o.object;
    s.led_latency_s = o.led_latency_s;
    s.camera_auto = false;  // the emulated camera has no auto exposure control to turn off
    s.serial = o.serial;
    return s;
}

}  // namespace

Renderer::Renderer(const RendererOptions& options, std::function<std::optional<Committed>()> streaming,
                   std::function<void(const Committed&, std::span<const std::uint8_t>)> submit)
    : options_(options), streaming_(std::move(streaming)), submit_(std::move(submit)) {
    const Illumination power_up({15, 15, 15});
    history_.push_back({-1e9, power_up});
    lit(power_up, false);
    for (const Illumination& s : options_.prerender) lit(s, false);
    thread_ = std::thread([this] { run(); });
}

Renderer::~Renderer() {
    stop_ = true;
    thread_.join();
}

void Renderer::set_illumination(const Illumination& setting) {
    std::lock_guard lock(mutex_);
    history_.push_back({clock_->now() + options_.led_latency_s, setting});
    while (history_.size() > 16) history_.pop_front();
}

SimDigit& Renderer::sim(bool vga) {
    if (!sims_[vga]) {
        SimDigitOptions o = sim_options(options_, vga);
        o.clock = sim_clocks_[vga] = make_virtual_clock();
        sims_[vga] = std::make_unique<SimDigit>(o);
    }
    return *sims_[vga];
}

// The frame the simulator renders under `setting` alone: with its virtual
// clock moved a second past the request, its newest frame is lit by nothing else.
const Renderer::Lit& Renderer::lit(const Illumination& setting, bool vga) {
    auto& cache = frames_[vga];
    const std::string key = setting.to_string();
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    SimDigit& s = sim(vga);
    s.set_illumination(setting);
    sim_clocks_[vga]->wait_until(sim_clocks_[vga]->now() + 1.0);
    const Frame f = s.grab();  // the newest frame, a second after the request
    Lit& l = cache[key];
    l.rgb = std::move(f.pixels);
    l.yuyv = rgb_to_yuyv(l.rgb, f.width, f.height);
    l.jpeg = rgb_to_jpeg(l.rgb, f.width, f.height, 85);
    return l;
}

std::vector<std::uint8_t> Renderer::compose(double t0, const Committed& c) {
    std::vector<Switch> history;
    {
        std::lock_guard lock(mutex_);
        history.assign(history_.begin(), history_.end());
    }
    const bool vga = c.mode.width == 640;
    const SimTiming timing = sim(vga).timing();
    const int height = c.mode.height;
    // Per row, the share of its exposure each setting lit, in 1/256ths.
    std::vector<std::vector<std::pair<const Lit*, int>>> rows(static_cast<std::size_t>(height));
    bool mixed = false;
    const Lit* only = nullptr;
    for (int r = 0; r < height; ++r) {
        const double start = t0 + r * timing.row_time_s, end = start + timing.nominal_exposure_s;
        for (std::size_t i = 0; i < history.size(); ++i) {
            const double from = std::max(start, history[i].at);
            const double to = std::min(end, i + 1 < history.size() ? history[i + 1].at : end);
            const int w = to > from ? int(std::lround(256.0 * (to - from) / (end - start))) : 0;
            if (w > 0) rows[std::size_t(r)].push_back({&lit(history[i].setting, vga), w});
        }
        const auto& row = rows[std::size_t(r)];
        if (row.size() != 1 || (only && row.front().first != only)) mixed = true;
        if (row.size() == 1) only = row.front().first;
    }
    if (!mixed && only) return c.mode.mjpeg ? only->jpeg : only->yuyv;
    // Mixed rows blend; YUYV mixes as RGB does, its conversion being affine.
    const bool yuyv = !c.mode.mjpeg;
    const std::size_t row_bytes = std::size_t(c.mode.width) * (yuyv ? 2 : 3);
    std::vector<std::uint8_t> out(row_bytes * std::size_t(height));
    for (int r = 0; r < height; ++r) {
        const auto& row = rows[std::size_t(r)];
        std::uint8_t* dst = out.data() + std::size_t(r) * row_bytes;
        const auto src = [&](const Lit* l) { return (yuyv ? l->yuyv : l->rgb).data() + std::size_t(r) * row_bytes; };
        if (row.size() == 1) {
            std::copy_n(src(row.front().first), row_bytes, dst);
            continue;
        }
        int total = 0;
        for (const auto& [l, w] : row) total += w;
        for (std::size_t k = 0; k < row_bytes; ++k) {
            int acc = 0;
            for (const auto& [l, w] : row) acc += w * src(l)[k];
            dst[k] = std::uint8_t(total ? (acc + total / 2) / total : 0);
        }
    }
    return yuyv ? out : rgb_to_jpeg(out, c.mode.width, c.mode.height, 85);
}

void Renderer::run() {
    std::uint64_t mjpeg_frames = 0;
    double next = clock_->now();
    while (!stop_) {
        const std::optional<Committed> c = streaming_();
        if (!c || paused_) {
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            next = clock_->now();
            continue;
        }
        const SimTiming timing = sim(c->mode.width == 640).timing();
        // Frame n starts exposing at `next`; it is read out a frame span later.
        const double period = 1.0 / c->fps();
        if (clock_->now() > next + period) next = clock_->now();  // fell behind: the camera streams on
        clock_->wait_until(next + timing.frame_span_s(timing.nominal_exposure_s));
        std::vector<std::uint8_t> encoded = compose(next, *c);
        next += period;
        if (c->mode.mjpeg && options_.corrupt_mjpeg_every > 0 &&
            ++mjpeg_frames % std::uint64_t(options_.corrupt_mjpeg_every) == 0)
            encoded.resize(encoded.size() / 2);  // cut short: the entropy-coded data ends mid-scan
        submit_(*c, encoded);
    }
}

}  // namespace vkfuse::emulator

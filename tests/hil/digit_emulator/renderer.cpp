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

Renderer::Renderer(const RendererOptions& options, std::function<std::optional<Committed>()> streaming, Send send)
    : options_(options), streaming_(std::move(streaming)), send_(std::move(send)) {
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

void Renderer::compose(double t0, const Committed& c, int from, int to, std::uint8_t* out) {
    // Copied per call, not per frame: a switch requested while the frame is
    // read out may light its later rows (the LED latency is configurable,
    // and can be shorter than a frame), as on the real sensor. At most 16
    // entries a chunk.
    std::vector<Switch> history;
    {
        std::lock_guard lock(mutex_);
        history.assign(history_.begin(), history_.end());
    }
    const bool vga = c.mode.width == 640, yuyv = !c.mode.mjpeg;
    const SimTiming timing = sim(vga).timing();
    const std::size_t row_bytes = std::size_t(c.mode.width) * (yuyv ? 2 : 3);
    std::vector<std::pair<const Lit*, int>> shares;  // the share of the row's exposure each setting lit, in 1/256ths
    for (int r = from; r < to; ++r) {
        const double start = t0 + r * timing.row_time_s, end = start + timing.nominal_exposure_s;
        shares.clear();
        for (std::size_t i = 0; i < history.size(); ++i) {
            const double lit_from = std::max(start, history[i].at);
            const double lit_to = std::min(end, i + 1 < history.size() ? history[i + 1].at : end);
            const int w = lit_to > lit_from ? int(std::lround(256.0 * (lit_to - lit_from) / (end - start))) : 0;
            if (w > 0) shares.push_back({&lit(history[i].setting, vga), w});
        }
        std::uint8_t* dst = out + std::size_t(r) * row_bytes;
        const auto src = [&](const Lit* l) { return (yuyv ? l->yuyv : l->rgb).data() + std::size_t(r) * row_bytes; };
        if (shares.size() == 1) {
            std::copy_n(src(shares.front().first), row_bytes, dst);
            continue;
        }
        // Mixed rows blend; YUYV mixes as RGB does, its conversion being affine.
        int total = 0;
        for (const auto& [l, w] : shares) total += w;
        for (std::size_t k = 0; k < row_bytes; ++k) {
            int acc = 0;
            for (const auto& [l, w] : shares) acc += w * src(l)[k];
            dst[k] = std::uint8_t(total ? (acc + total / 2) / total : 0);
        }
    }
}

// Each transfer's bytes are sent once the last row in them is exposed.
void Renderer::stream_yuyv(double t0, const Committed& c) {
    const SimTiming timing = sim(c.mode.width == 640).timing();
    const std::size_t row_bytes = std::size_t(c.mode.width) * 2;
    std::vector<std::uint8_t> frame(row_bytes * std::size_t(c.mode.height));
    int rows_done = 0;
    send_(c, frame.size(), [&](std::size_t bytes) {
        const int rows = int((bytes + row_bytes - 1) / row_bytes);
        if (rows > rows_done) {
            clock_->wait_until(t0 + (rows - 1) * timing.row_time_s + timing.nominal_exposure_s);
            compose(t0, c, rows_done, rows, frame.data());
            rows_done = rows;
        }
        return frame.data();
    });
}

void Renderer::stream_mjpeg(double t0, const Committed& c) {
    const SimTiming timing = sim(c.mode.width == 640).timing();
    clock_->wait_until(t0 + timing.frame_span_s(timing.nominal_exposure_s));
    std::vector<std::uint8_t> rgb(std::size_t(c.mode.width) * std::size_t(c.mode.height) * 3);
    compose(t0, c, 0, c.mode.height, rgb.data());
    std::vector<std::uint8_t> jpeg = rgb_to_jpeg(rgb, c.mode.width, c.mode.height, 85);
    if (options_.corrupt_mjpeg_every > 0 && ++mjpeg_frames_ % std::uint64_t(options_.corrupt_mjpeg_every) == 0)
        jpeg.resize(jpeg.size() / 2);  // cut short: the entropy-coded data ends mid-scan
    send_(c, jpeg.size(), [&](std::size_t) { return jpeg.data(); });
}

void Renderer::run() {
    double next = clock_->now();
    while (!stop_) {
        const std::optional<Committed> c = streaming_();
        if (!c || paused_) {
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            next = clock_->now();
            continue;
        }
        // Frame n starts exposing at `next`, frame n + 1 a period later.
        const double period = 1.0 / c->fps();
        if (clock_->now() > next + period) next = clock_->now();  // fell behind: the camera streams on
        const double t0 = next;
        next += period;
        if (c->mode.mjpeg) stream_mjpeg(t0, *c);
        else stream_yuyv(t0, *c);
    }
}

}  // namespace vkfuse::emulator

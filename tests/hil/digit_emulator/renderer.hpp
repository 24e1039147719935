// renderer.hpp - the emulated DIGIT's camera. Each LED setting the host asks
// for is rendered once by the simulated DIGIT (SimDigit, the whole frame lit
// by it) and kept; every streamed frame is then composed row by row from
// those, on the real clock, with the simulator's LED latency and rolling
// shutter: a row exposed across a switch mixes the two settings in the
// proportion of its exposure each lit. Rendering per frame would be
// physically the same but, under an emulated CPU (the HIL virtual machine
// has no KVM), takes about a second a frame.
//
// A YUYV frame leaves as its rows are read out, as a streaming camera's do:
// the host's first transfer of a frame takes its first rows once they are
// exposed, so uvcvideo, which stamps a frame when its first bytes arrive,
// stamps it a row exposure after the frame started. An MJPEG frame leaves
// once the whole frame is read out and compressed.
#pragma once
#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "uvc_camera.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::emulator {

struct RendererOptions {
    double led_latency_s = 0.025;
    std::string object = "coin";
    int corrupt_mjpeg_every = 0;  // every Nth MJPEG frame cut short (0: never)
    std::string serial;
    std::vector<Illumination> prerender;  // settings rendered before streaming starts
};

class Renderer {
public:
    // streaming() says what to stream; send() streams each frame, taking its
    // bytes as the host asks for them (UvcCamera::send_frame).
    using Send = std::function<bool(const Committed&, std::size_t frame_size, const FrameBytes& frame)>;
    Renderer(const RendererOptions& options, std::function<std::optional<Committed>()> streaming, Send send);
    ~Renderer();  // stops the thread

    // The host's LED request, now: it lights rows from now + the latency on.
    void set_illumination(const Illumination& setting);
    // Stops or resumes sending frames (the camera goes silent; control
    // requests are still answered).
    void pause(bool paused) { paused_ = paused; }
    bool paused() const { return paused_; }

private:
    struct Switch {
        double at;  // when the setting starts to light the gel (real clock)
        Illumination setting;
    };
    // One setting's frame in each encoding the stream may ask for.
    struct Lit {
        std::vector<std::uint8_t> rgb, yuyv, jpeg;
    };
    void run();
    SimDigit& sim(bool vga);
    const Lit& lit(const Illumination& setting, bool vga);
    // Rows [from, to) of the frame starting at t0, in the committed encoding
    // (YUYV, or RGB for MJPEG), into `out` (the whole frame): a setting's own
    // rows where one lit a row alone, else mixed.
    void compose(double t0, const Committed& c, int from, int to, std::uint8_t* out);
    void stream_yuyv(double t0, const Committed& c);
    void stream_mjpeg(double t0, const Committed& c);

    RendererOptions options_;
    std::function<std::optional<Committed>()> streaming_;
    Send send_;
    std::uint64_t mjpeg_frames_ = 0;  // renderer thread only
    std::shared_ptr<Clock> clock_ = make_real_clock();
    std::unique_ptr<SimDigit> sims_[2];  // [vga], each on a virtual clock of its own; renderer thread only
    std::shared_ptr<Clock> sim_clocks_[2];

    std::mutex mutex_;  // history_
    std::deque<Switch> history_;
    std::map<std::string, Lit> frames_[2];  // [vga], per setting; renderer thread only

    std::atomic<bool> stop_{false}, paused_{false};
    std::thread thread_;
};

}  // namespace vkfuse::emulator

// vkfuse/sensor/switching.hpp - frames lit entirely by one LED setting, from a sensor
// whose LEDs switch some time after a request and whose camera has a rolling
// shutter (rows start exposing one after another, so a frame exposed across a
// switch is part old light, part new).
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/sensor/clock.hpp"
#include "vkfuse/sensor/illumination.hpp"
#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse {

// What start-up calibration learnt about one sensor, in seconds of its clock.
// Two bounds are all a schedule needs: how long after a request frames are
// lit entirely by the new setting (LED latency, plus any settling of the
// camera's own auto exposure), and how long after a frame's timestamp the next
// request may be made without touching that frame (its rolling readout and
// exposure, minus the shortest LED latency; negative when the latency is the
// longer). The two cannot be told apart further from frame timestamps alone,
// and need not be.
struct SwitchTiming {
    double frame_period = 0;  // median timestamp spacing per frame of the sensor's counter
    double jitter = 0;        // largest deviation of a spacing from frame_period
    double delivery = 0;      // median time from a frame's timestamp until grab() returned it
    double latency_max = 0;   // frames stamped >= request + latency_max are lit by the request alone
    double clearance = 0;     // a request at t leaves frames stamped <= t - clearance untouched
    int trials = 0;           // switches observed

    double first_lit(double request_time) const { return request_time + latency_max; }
    // The earliest time the next setting may be requested without touching a
    // frame stamped ts.
    double next_request(double ts) const { return ts + clearance; }
    // The latest timestamp a frame may have and still be untouched by a
    // setting requested at request_time (the inverse of next_request).
    double last_untouched(double request_time) const { return request_time - clearance; }
};

struct SwitchCalibration {
    int trials = 16;         // switches between the two settings (half each way), at spread phases
    double settle_s = 0.25;  // sensor time to wait before trusting a steady frame
    double timeout_s = 2.0;  // sensor time one switch may take to show (and 12 frames at least)
    // A row whose mean moved less than this fraction of the old->new change is
    // "unchanged" (noise); the timing bounds are widened by the same fraction
    // of a frame period, so a slightly touched row can never pass as clean.
    double tolerance = 0.03;
    // Each switch's wait for its phase and its request run under SCHED_FIFO
    // at this priority (Switcher::set_switch_priority says why; 0: the normal
    // scheduler): a thread a busy host wakes late bunches the phases
    // together, and the bounds they give come out looser than the sensor's.
    int request_priority = 0;
};

// Toggles the LEDs between all off and all at maximum (the two most different
// settings any LED layout has) and watches per-row frame means move from one
// steady profile to the other. For each switch requested at t, the first frame
// matching the new profile bounds latency_max (its timestamp - t) and the last
// frame still entirely old bounds clearance (t - its timestamp: it ended
// before the switch landed). Each bound is the tightest over the switches of
// one direction and the looser of the two directions: with the LEDs off an
// auto-exposing camera exposes longest, and switching on takes it longest to
// settle. Requests are made at phases spread over a frame period so the
// bounds narrow to a fraction of it. The scene must stay still meanwhile.
// Throws Error naming the serial when the frames never settle or do not
// respond to the LEDs.
SwitchTiming measure_switch_timing(Sensor& sensor, Clock& clock, const SwitchCalibration& options = {});

// Which frames a sensor's fused image is made of.
enum class FusionWindow {
    // One clean frame per setting, each taken for that cycle: K clean frames
    // per fused image (the paper's way).
    Cycle,
    // The newest clean frame of each setting, fused at every new clean frame
    // (Switcher::next_window): K times the fused images from the same frames,
    // each up to K - 1 clean-frame periods apart.
    Sliding,
};
std::string_view to_string(FusionWindow window);  // "cycle", "sliding"
// Throws Error(InvalidArgument) "<what> <name>: expected cycle or sliding".
FusionWindow parse_fusion_window(std::string_view name, std::string_view what = "--window");

// The most the frames of one sliding window (Switcher::next_window) may span,
// from the oldest frame's timestamp to the newest's: one sequence period (K
// switches, each as soon as the last frame allows) plus the LED latency.
double window_bound(const SwitchTiming& timing, std::size_t settings);

// The newest timestamp among frames (when their window was complete), and
// how long before it the oldest was taken: what window_bound limits (0 for
// no frames).
double newest_timestamp(std::span<const Frame> frames);
double window_span(std::span<const Frame> frames);

// Fetches frames lit entirely by requested settings from one sensor (used by
// one thread). Two ways to judge a frame:
//  - by timing (a live sensor): a frame belongs to the setting requested at t
//    when its timestamp is >= timing.first_lit(t) and every row finished
//    before the next request could land;
//  - by label (a recorded dataset): a frame belongs to the setting its
//    Frame::illumination names; no clock or timing is needed.
class Switcher {
public:
    Switcher(Sensor& sensor, std::shared_ptr<Clock> clock, const SwitchTiming& timing);
    static Switcher labelled(Sensor& sensor);
    ~Switcher();
    Switcher(Switcher&&) noexcept;
    Switcher& operator=(Switcher&&) noexcept;

    // Switches to setting and returns the next n frames lit entirely by it.
    std::vector<Frame> capture(const Illumination& setting, int n);

    // One frame per setting of sequence (slot k lit entirely by sequence[k]),
    // in the order the cycle is complete. By timing, the next setting is
    // requested as early as the frame in hand allows, before that frame is
    // even read out, and frame times are predicted from the frame period; a
    // frame that misses its window (dropped frame, late thread) is requested
    // again. Throws Error naming the serial after repeated misses. Call with
    // the same sequence every time.
    std::vector<Frame> next_cycle(const IlluminationSequence& sequence);

    // A sliding window over the same stream of clean frames (by timing only):
    // the newest frame of each slot of sequence, returned once for every new
    // clean frame from the first moment every slot has one, so K settings
    // give K windows per cycle. Frames enter in the order of their slots
    // (cycle c's slot k after cycle c's slot k - 1), so a frame that missed
    // its window makes the windows wait for it. A window whose frames span
    // more than window_bound(timing, K) is not returned but counted
    // (windows_held()): that happens when a frame came late. The same
    // sequence every time, as for next_cycle; a capture() in between starts
    // the window over.
    std::vector<Frame> next_window(const IlluminationSequence& sequence);
    std::uint64_t windows_held() const;

    // By timing: each LED switch request, and the wait for its moment, runs
    // under real-time scheduling (SCHED_FIFO at priority, 1..99) on the
    // calling thread, and nothing else it does. A request has about a
    // millisecond of slack (SwitchTiming::clearance); a busy host's scheduler
    // wakes a normal thread later than that, and each late request costs a
    // frame. 0 (the default): the normal scheduler. Returns how requests run:
    // "fifo N", "normal", or "normal (fifo N refused: why)" when the thread
    // may not (no CAP_SYS_NICE and RLIMIT_RTPRIO below N).
    std::string set_switch_priority(int priority);

    // Frames grabbed and requests made so far (what a cycle cost).
    std::uint64_t frames_grabbed() const;
    std::uint64_t requests_made() const;

    struct Impl;

private:
    explicit Switcher(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse

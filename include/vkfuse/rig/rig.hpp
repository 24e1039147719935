// vkfuse/rig/rig.hpp - S sensors cycling through their LED sequence, one capture
// thread each, fused together every cycle with one GPU submit.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/core/skip.hpp"
#include "vkfuse/sensor/clock.hpp"
#include "vkfuse/sensor/illumination.hpp"
#include "vkfuse/sensor/sensor.hpp"
#include "vkfuse/sensor/switching.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse {

// A sensor and the clock its frame timestamps are on (the rig reads it to
// time LED requests). The clock may be null when frames are judged by label.
struct RigSensor {
    std::shared_ptr<Sensor> sensor;
    std::shared_ptr<Clock> clock;
};

enum class FrameJudging {
    Timing,  // live sensors: measure switch timing at start-up, then trust frame timestamps
    Label,   // recorded datasets: trust Frame::illumination; no calibration
};

// Sensors one rig drives at most: each has a capture thread and its own
// buffers in one plan.
inline constexpr std::size_t kMaxRigSensors = 64;

struct RigConfig {
    FusionSpec fusion;
    IlluminationSequence sequence;  // K settings, one frame each per cycle
    FrameJudging judging = FrameJudging::Timing;
    // Which frames each fused image is made of (FusionWindow). Sliding with
    // frames judged by label: a replay of a sliding run, whose windows were
    // recorded whole, played as they were recorded.
    FusionWindow window = FusionWindow::Cycle;
    SwitchCalibration calibration;
    // Frames per setting averaged into each sensor's background model before
    // the first cycle (with nothing pressed); 0: no background, no
    // background_diff in the metrics.
    int background_frames = 0;
    double cycle_timeout_s = 5.0;     // wall-clock time a cycle waits for a sensor
    double startup_timeout_s = 60.0;  // wall-clock time for calibration and background
    bool want_fused = true;           // read fused images back (else metrics only)
    // false: a capture host. Cycles are assembled, judged and returned with
    // their frames (and backgrounds taken, for on_background) but nothing is
    // fused or measured: no engine, no device needed; skip must be off.
    bool fuse = true;
    // The metrics of each cycle (PlanConfig::metrics); background_diff only
    // when there is a background (background_frames > 0).
    MetricSet metrics = MetricSet::all();
    // Skipping idle sensors (PlanConfig::skip): each sensor's cycles are
    // compared with its background frames' mean and noise, so it needs
    // background_frames >= 2.
    SkipConfig skip;
    // With skip on and frames judged by timing: a sensor whose last cycle
    // was idle captures only the first setting of the sequence (a "watch"
    // cycle: no LED switching, no frames lost to it) until that frame
    // changes; the cycle after it captures and fuses the whole sequence again.
    // Off for a run whose frames are recorded, so that every cycle of the
    // dataset holds every setting, and with sliding windows (a window needs
    // every setting's newest frame).
    bool watch_when_idle = true;
    // 2: the rig submits cycle c + 1 to the device before it returns cycle c
    // (PlanConfig::cycles_in_flight), so the device fuses c + 1 while the
    // caller handles c; each result then comes one cycle's capture later.
    // Needs a GPU context and skip off (a skipping plan keeps its references
    // and held results once, for 1 cycle in flight). 1: each next() is one
    // round trip.
    int cycles_in_flight = 1;
    // Frames judged by timing: each sensor's LED switch requests run under
    // real-time scheduling (SCHED_FIFO) at this priority, 1..99, for the
    // moment each takes (Switcher::set_switch_priority says why); 0: the
    // normal scheduler. Only on a clock that passes on its own
    // (Clock::passes_on_its_own): a virtual clock's requests are never late. Refused (no CAP_SYS_NICE or RLIMIT_RTPRIO),
    // the rig runs as with 0 and switch_scheduling() says so.
    int switch_priority = 0;

    // Called on a sensor's capture thread with each setting's background
    // frames (e.g. to record them), then once when its background is done
    // and before its first cycle (e.g. to press the object). Never called
    // after the Rig is destroyed.
    std::function<void(std::size_t sensor, const Illumination& setting, const std::vector<Frame>& frames)>
        on_background;
    std::function<void(std::size_t sensor)> after_background;
};

enum class SensorStatus {
    Ok,       // fresh frames fused this cycle
    Timeout,  // nothing new within cycle_timeout_s; not waited for again until it delivers
    // Threw: dropped for the rest of the run; except a sensor that threw
    // Error(Unplugged) or Error(Timeout) (a DIGIT unplugged, or silent): it is
    // reported Failed or Timeout every cycle while its capture thread asks it
    // for frames again, and rejoins once it delivers.
    Failed,
};

struct SensorCycle {
    std::string serial;
    SensorStatus status = SensorStatus::Ok;
    std::string error;             // when not Ok: one line that names the serial
    std::vector<Frame> frames;     // when Ok: the K frames fused, slot k lit by sequence[k]
    Metrics metrics;               // when Ok
    const Image* fused = nullptr;  // when Ok and want_fused; valid until the next cycle
    SkipOutcome skip;              // when Ok: idle (its fused background returned) or fused
    // When Ok: only the first setting was captured (frames holds that one
    // frame; see RigConfig::watch_when_idle). Such a cycle is always idle;
    // where its frame changed (skip.changed_fraction > 0) the next cycle
    // captures the whole sequence and is fused.
    bool watch = false;
    // When Ok: the newest frame's timestamp (when the window was complete),
    // and how long before it the oldest was taken (0 for a watch cycle).
    double newest_timestamp() const;
    double window_span_s() const;
};

struct CycleResult {
    std::uint64_t cycle = 0;  // from 0
    std::vector<SensorCycle> sensors;
    double capture_wait_s = 0;  // wall time spent waiting for the sensors' frames
    double fuse_s = 0;          // wall time of the one submit and its wait (or the CPU fusion)
};

// Every sensor has its own capture thread that calibrates it (FrameJudging::
// Timing), takes its background frames, then assembles cycles back to back:
// the thread captures cycle c + 1 while cycle c is fused. next() waits until
// every sensor still in step has a cycle ready (or cycle_timeout_s passes),
// fuses all of them with one Plan::run, and reports each sensor.
//
// A sensor that is late gets status Timeout and its slot in the plan is
// filled with its last good frames (black before it had any); its result is
// not reported as fused. Later cycles do not wait for it until it delivers
// again, so one stalled sensor costs the others one timeout, once. A sensor
// that throws is Failed for the rest of the run, with its message (naming its
// serial) in every later cycle. While every sensor is gone (unplugged or
// silent, so able to come back) a cycle waits its timeout for one to return.
// All sensors must share one frame size.
class Rig {
public:
    // context null: fuse with the CPU reference path instead of the GPU.
    Rig(Context* context, RigConfig config, std::vector<RigSensor> sensors);
    ~Rig();  // stops the capture threads (a thread stuck in a sensor call is left behind, detached)
    Rig(const Rig&) = delete;
    Rig& operator=(const Rig&) = delete;

    // Starts the capture threads and waits (at most startup_timeout_s) until
    // every sensor is calibrated and has its background. Throws Error when no
    // sensor got that far.
    void start();
    // The next cycle (start() first).
    CycleResult next();

    std::size_t sensors() const;
    std::string serial(std::size_t sensor) const;
    // What calibration measured (nullopt when judging by label or not yet done).
    std::optional<SwitchTiming> timing(std::size_t sensor) const;
    // How its LED switch requests run (RigConfig::switch_priority): "fifo N",
    // "normal", or "normal (fifo N refused: why)"; empty until calibrated,
    // and when judging by label.
    std::string switch_scheduling(std::size_t sensor) const;
    FusionWindow window() const;  // RigConfig::window
    // The most one window's frames may span (vkfuse::window_bound of the
    // sensor's timing and the sequence); nullopt when judging by label or
    // not calibrated yet.
    std::optional<double> window_bound(std::size_t sensor) const;
    // Sliding windows not fused because their frames spanned more than
    // window_bound (a frame came late), so far.
    std::uint64_t windows_held(std::size_t sensor) const;
    // True when every sensor has failed and no cycle is left to take (or, with
    // two cycles in flight, to return): nothing more will come.
    bool all_failed() const;
    // Cycles the rig keeps on the device at once (RigConfig::cycles_in_flight;
    // 1 on the CPU path).
    int cycles_in_flight() const;
    // Fusion submits so far: one per cycle for all sensors together.
    std::uint64_t submits() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

std::string_view to_string(SensorStatus status);  // "ok", "timeout", "failed"

}  // namespace vkfuse

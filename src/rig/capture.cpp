// The capture thread of one sensor (rig/hub.hpp).
#include <map>
#include <utility>

#include "rig/hub.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/core/skip.hpp"

namespace vkfuse::rig {
namespace {

// Runs f under the work lock unless the rig is stopping; false if it was.
template <class F>
bool guarded(Hub& hub, F&& f) {
    std::lock_guard lock(hub.work_mutex);
    if (hub.stop) return false;
    f();
    return true;
}

// A sensor that may come back: unplugged (a DIGIT looks for its serial again
// on the next grab) or silent for longer than it waits.
bool recoverable(const Error& e) { return e.kind() == ErrorKind::Unplugged || e.kind() == ErrorKind::Timeout; }

Switcher make_switcher(const CaptureJob& job) {
    Sensor& sensor = *job.sensor.sensor;
    if (job.config->judging == FrameJudging::Label) return Switcher::labelled(sensor);
    if (!job.sensor.clock) throw Error(ErrorKind::InvalidArgument, "judging frames by timing needs the sensor's clock");
    // A virtual clock's requests are never late.
    const int priority = job.sensor.clock->passes_on_its_own() ? job.config->switch_priority : 0;
    SwitchCalibration calibration = job.config->calibration;
    calibration.request_priority = priority;
    const SwitchTiming timing = measure_switch_timing(sensor, *job.sensor.clock, calibration);
    Switcher switcher(sensor, job.sensor.clock, timing);
    const std::string scheduling = switcher.set_switch_priority(priority);
    {
        std::lock_guard lock(job.hub->mutex);
        job.hub->slots[job.index].timing = timing;
        job.hub->slots[job.index].switch_scheduling = scheduling;
    }
    return switcher;
}

// One mean per distinct setting of the sequence, with nothing pressed.
// Returns false if the rig stopped meanwhile.
// With skipping on, also each setting's per-pixel standard deviation.
bool capture_background(const CaptureJob& job, Switcher& switcher, std::vector<Image>& out,
                        std::vector<Image>& deviations) {
    const RigConfig& cfg = *job.config;
    std::map<std::string, std::pair<Image, Image>> means;
    const bool skipping = cfg.skip.policy != SkipPolicy::Off;
    for (const Illumination& setting : cfg.sequence) {
        auto known = means.find(setting.to_string());
        if (known != means.end()) {
            out.push_back(known->second.first);
            if (skipping) deviations.push_back(known->second.second);
            continue;
        }
        const std::vector<Frame> frames = switcher.capture(setting, cfg.background_frames);
        std::vector<FrameView> views;
        for (const Frame& f : frames) views.push_back(f.view());
        Image mean;
        const bool ran = guarded(*job.hub, [&] {
            if (cfg.on_background) cfg.on_background(job.index, setting, frames);
            if (cfg.fuse) mean = job.hub->average(views);
        });
        if (!ran) return false;
        Image deviation = skipping && cfg.fuse ? background_deviation(views, mean) : Image();
        means.emplace(setting.to_string(), std::pair(mean, deviation));
        out.push_back(std::move(mean));
        if (skipping) deviations.push_back(std::move(deviation));
    }
    return true;
}

std::optional<SwitchTiming> slot_timing(Hub& hub, const SensorSlot& slot) {
    std::lock_guard lock(hub.mutex);
    return slot.timing;
}

// Hands one cycle to the rig, waiting while its mailbox is full.
bool deliver(Hub& hub, SensorSlot& slot, std::vector<Frame> frames, std::uint64_t windows_held) {
    std::unique_lock lock(hub.mutex);
    hub.changed.wait(lock, [&] { return hub.stop || slot.ready.size() < kMailboxCycles; });
    if (hub.stop) return false;
    slot.ready.push_back(std::move(frames));
    slot.windows_held = windows_held;
    slot.lost.reset();
    hub.changed.notify_all();
    return true;
}

void run_capture(const CaptureJob& job) {
    Hub& hub = *job.hub;
    SensorSlot& slot = hub.slots[job.index];
    Switcher switcher = make_switcher(job);
    std::vector<Image> background, deviation;
    if (job.config->background_frames > 0 && !capture_background(job, switcher, background, deviation)) return;
    {
        std::lock_guard lock(hub.mutex);
        slot.background = std::move(background);
        slot.deviation = std::move(deviation);
        slot.background_done = true;
    }
    hub.changed.notify_all();
    const auto& after = job.config->after_background;
    if (!guarded(hub, [&] {
            if (after) after(job.index);
        }))
        return;
    const RigConfig& cfg = *job.config;
    // A replay's windows were recorded whole: they come as cycles.
    const bool sliding = cfg.window == FusionWindow::Sliding && cfg.judging == FrameJudging::Timing;
    const bool may_watch = cfg.watch_when_idle && cfg.skip.policy != SkipPolicy::Off &&
                           cfg.judging == FrameJudging::Timing && cfg.sequence.size() > 1 && !sliding;
    // Whether delivery n watches depends on the verdicts: after a watch
    // cycle, on its verdict (a change is followed at once by a whole
    // sequence); after a whole cycle, on the verdict two back, and only where
    // that one was idle also on the last (the capture of a busy sensor keeps
    // running a cycle ahead of its fusion). On a virtual clock it waits for
    // them, so that the run stays deterministic. On a clock that passes on its
    // own it never waits for a whole cycle's: a verdict not yet given counts
    // as not idle, since a capture held back past its next switch request
    // loses frames (and the watch that waiting could bring is a cycle late).
    const bool wait_for_verdicts = !job.sensor.clock || !job.sensor.clock->passes_on_its_own();
    bool last_watched = false;
    std::uint64_t held_before = 0;  // windows held by switchers an error replaced
    for (std::uint64_t n = 0;;) {
        bool watch = false;
        if (may_watch) {
            std::unique_lock lock(hub.mutex);
            auto verdict = [&](std::uint64_t d, bool wait) {
                if (!wait && slot.judged <= d) return false;
                hub.changed.wait(lock, [&] { return hub.stop || slot.judged > d; });
                return !hub.stop && d >= slot.verdicts_from && slot.idle_verdict(d);
            };
            if (last_watched)
                watch = verdict(n - 1, true);
            else if (n >= 2)
                watch = verdict(n - 2, wait_for_verdicts) && verdict(n - 1, wait_for_verdicts);
            if (hub.stop) return;
        }
        std::vector<Frame> frames;
        try {
            frames = watch     ? switcher.capture(cfg.sequence.front(), 1)
                     : sliding ? switcher.next_window(cfg.sequence)
                               : switcher.next_cycle(cfg.sequence);
        } catch (const Error& e) {
            if (!recoverable(e)) throw;
            {
                std::lock_guard lock(hub.mutex);
                if (hub.stop) return;
                slot.lost = e.kind() == ErrorKind::Unplugged ? SensorStatus::Failed : SensorStatus::Timeout;
                slot.error = with_serial(slot.serial, e.what());
            }
            hub.changed.notify_all();
            // The cycle in hand is abandoned with the scheduler's state; the
            // measured timing still holds for the same sensor.
            if (const auto timing = slot_timing(hub, slot)) {
                held_before += switcher.windows_held();
                switcher = Switcher(*job.sensor.sensor, job.sensor.clock, *timing);
            }
            continue;
        }
        if (!deliver(hub, slot, std::move(frames), held_before + switcher.windows_held())) return;
        last_watched = watch;
        ++n;
    }
}

}  // namespace

Image Hub::average(std::span<const FrameView> frames) {
    if (!context) return convert<float>(background_mean_reference(frames));
    if (!model || model->frames() != int(frames.size()))
        model = std::make_unique<BackgroundModel>(*context, frames[0].height, frames[0].width, frames[0].channels,
                                                  int(frames.size()));
    return model->mean(frames);
}

std::string with_serial(const std::string& serial, const std::string& message) {
    return message.rfind(serial, 0) == 0 ? message : serial + ": " + message;
}

void capture_main(CaptureJob job) {
    Hub& hub = *job.hub;
    SensorSlot& slot = hub.slots[job.index];
    std::string error;
    try {
        run_capture(job);
    } catch (const std::exception& e) {
        error = e.what();
        if (error.empty()) error = "unknown error";
    } catch (...) {
        error = "unknown error";
    }
    std::lock_guard lock(hub.mutex);
    if (!error.empty()) {
        slot.failed = true;
        slot.error = with_serial(slot.serial, error);
    }
    slot.exited = true;
    hub.changed.notify_all();
}

}  // namespace vkfuse::rig

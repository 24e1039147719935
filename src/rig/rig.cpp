// Rig: capture threads feed a mailbox each; next() fuses whatever the cycle
// brought with one submit (include/vkfuse/rig/rig.hpp).
#include "vkfuse/rig/rig.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <thread>

#include "core/deadline.hpp"
#include "io/png.hpp"
#include "rig/engine.hpp"
#include "rig/hub.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace {

using WallClock = std::chrono::steady_clock;

WallClock::time_point after(double seconds) {
    return deadline_after<WallClock>(WallClock::now(), seconds);
}

double seconds_since(WallClock::time_point t) { return std::chrono::duration<double>(WallClock::now() - t).count(); }

void check_config(const RigConfig& cfg, const std::vector<RigSensor>& sensors, const Context* context) {
    if (sensors.empty()) throw Error(ErrorKind::InvalidArgument, "rig: no sensors");
    if (sensors.size() > kMaxRigSensors)
        throw Error(ErrorKind::InvalidArgument, "rig: " + std::to_string(sensors.size()) + " sensors; at most " +
                                                    std::to_string(kMaxRigSensors));
    if (cfg.sequence.empty()) throw Error(ErrorKind::InvalidArgument, "rig: empty illumination sequence");
    if (cfg.sequence.size() > kMaxSequenceSettings)
        throw Error(ErrorKind::InvalidArgument, "rig: " + std::to_string(cfg.sequence.size()) +
                                                    " settings in one cycle; at most " +
                                                    std::to_string(kMaxSequenceSettings));
    if (cfg.background_frames < 0) throw Error(ErrorKind::InvalidArgument, "rig: background_frames must be >= 0");
    if (!(cfg.cycle_timeout_s > 0) || !(cfg.startup_timeout_s > 0))
        throw Error(ErrorKind::InvalidArgument, "rig: timeouts must be > 0");
    if (cfg.skip.policy != SkipPolicy::Off && cfg.background_frames < 2)
        throw Error(ErrorKind::InvalidArgument, "rig: skip " + std::string(to_string(cfg.skip.policy)) +
                                                    " needs at least 2 background frames per setting");
    for (const RigSensor& s : sensors)
        if (!s.sensor) throw Error(ErrorKind::InvalidArgument, "rig: null sensor");
    if (!cfg.fuse && cfg.skip.policy != SkipPolicy::Off)
        throw Error(ErrorKind::InvalidArgument, "rig: skip " + std::string(to_string(cfg.skip.policy)) +
                                                    " needs fusion on (a rig that fuses nothing has nothing to skip)");
    if (cfg.cycles_in_flight != 1 && cfg.cycles_in_flight != 2)
        throw Error(ErrorKind::InvalidArgument, "rig: cycles_in_flight must be 1 or 2, got " +
                                                    std::to_string(cfg.cycles_in_flight));
    if (cfg.switch_priority < 0 || cfg.switch_priority > 99)
        throw Error(ErrorKind::InvalidArgument, "rig: switch_priority must be 0..99, got " + std::to_string(cfg.switch_priority));
    if (cfg.cycles_in_flight == 2 && !context)
        throw Error(ErrorKind::InvalidArgument, "rig: 2 cycles in flight need a GPU context (the CPU path fuses "
                                                "each cycle as it is taken)");
    if (cfg.cycles_in_flight == 2 && cfg.skip.policy != SkipPolicy::Off)
        throw Error(ErrorKind::InvalidArgument, "rig: 2 cycles in flight need skip off (a skipping plan keeps "
                                                "its references and held results once, for 1 cycle in flight)");
}

// The first frame of the oldest cycle in a sensor's mailbox, if any.
const Frame* first_ready_frame(const rig::SensorSlot& slot) {
    return slot.ready.empty() || slot.ready.front().empty() ? nullptr : &slot.ready.front().front();
}

// Replayed frames recorded for a later cycle than the one being assembled:
// the sensor missed this cycle when recorded, so it misses it again.
bool for_a_later_cycle(const std::vector<Frame>& frames, std::uint64_t cycle) {
    return !frames.empty() && frames.front().recorded_cycle > std::int64_t(cycle);
}

}  // namespace

struct Rig::Impl {
    Context* context;
    std::shared_ptr<const RigConfig> cfg;
    std::vector<RigSensor> sensors;
    std::shared_ptr<rig::Hub> hub = std::make_shared<rig::Hub>();
    std::vector<std::thread> threads;
    int height = 0, width = 0;
    std::unique_ptr<rig::Engine> engine;     // one submit per cycle for all sensors; null: fusion off
    std::unique_ptr<rig::Engine> bg_engine;  // fuses background means the way frames are fused
    std::vector<std::vector<Frame>> last_good;
    std::vector<bool> lagging;  // timed out and not delivered since: not waited for
    // Delivered numbered cycles: a recording's (Frame::recorded_cycle), placed
    // in their recorded cycle, or another host's rig's (Frame::origin), fused
    // in step with that rig's other sensors. Always waited for while not
    // lost: a numbered cycle that never comes shows when the sensor's next
    // one is for a later cycle, so no timeout is needed to go on without it,
    // and a sensor that sat one out is not left behind the others.
    std::vector<bool> numbered;
    std::vector<std::uint8_t> black;
    // Watch cycles: per sensor, its background means rounded to 8 bits (what
    // stands in for the settings a watch cycle did not capture: they score
    // at most half a level from the means), and its last idle result.
    std::vector<std::vector<std::vector<std::uint8_t>>> fill;
    std::vector<std::optional<Metrics>> idle_metrics;
    std::vector<const Image*> idle_image;
    std::uint64_t cycle = 0;
    bool started = false;
    // Two cycles in flight: the cycle submitted and not yet returned.
    std::optional<CycleResult> ahead;

    Impl(Context* c, RigConfig config, std::vector<RigSensor> s);
    PlanConfig plan_config(PixelType input, bool metrics) const;
    bool cycle_ready() const;  // call with hub->mutex held
    void await_startup();
    void take_cycle(CycleResult& result);
    // The next cycle taken from the sensors and submitted to the engine.
    CycleResult start_cycle();
    // Each sensor's results of the cycle the engine collected last.
    void report(CycleResult& result);
    void apply_new_backgrounds();
    void stop_threads();
    std::vector<FrameView> views_for(const std::vector<SensorCycle>& sensors) const;
};

Rig::Impl::Impl(Context* c, RigConfig config, std::vector<RigSensor> s)
    : context(c), cfg(std::make_shared<const RigConfig>(std::move(config))), sensors(std::move(s)) {
    check_config(*cfg, sensors, context);
    hub->context = context;
    hub->slots.resize(sensors.size());
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        const SensorInfo info = sensors[i].sensor->info();
        for (const Illumination& setting : cfg->sequence) setting.check(info.leds);
        if (i == 0) {
            height = info.height;
            width = info.width;
        } else if (info.height != height || info.width != width) {
            throw Error(ErrorKind::Shape, info.serial + ": frames of " + std::to_string(info.width) + "x" +
                                              std::to_string(info.height) + " differ from " + hub->slots[0].serial +
                                              "'s " + std::to_string(width) + "x" + std::to_string(height));
        }
        hub->slots[i].serial = info.serial;
    }
    if (cfg->fuse) engine = rig::make_engine(context, plan_config(PixelType::U8, true));
    if (engine && cfg->background_frames > 0) {
        const Image zero(height, width, 3);  // until a sensor's own background is in
        const SkipReference black{std::vector<Image>(cfg->sequence.size(), zero),
                                  std::vector<Image>(cfg->sequence.size(), zero)};
        // On a device, the backgrounds' plan fuses these black means once
        // now: a driver that compiles its shaders at their first dispatch does
        // so here, not while the first cycles wait for the real backgrounds.
        // On the CPU there is nothing to warm, and black fuses to black.
        if (context) {
            bg_engine = rig::make_engine(context, plan_config(PixelType::F32, false));
            bg_engine->run(std::vector<FrameView>(sensors.size() * cfg->sequence.size(), FrameView::of(zero)));
        }
        for (std::size_t i = 0; i < sensors.size(); ++i) {
            engine->set_background(int(i), bg_engine ? bg_engine->fused(int(i)) : zero);
            if (cfg->skip.policy != SkipPolicy::Off) engine->set_skip_reference(int(i), black);
        }
    }
    last_good.resize(sensors.size());
    fill.resize(sensors.size());
    idle_metrics.resize(sensors.size());
    idle_image.assign(sensors.size(), nullptr);
    lagging.assign(sensors.size(), false);
    numbered.assign(sensors.size(), false);
    black.assign(std::size_t(height) * std::size_t(width) * 3, 0);
}

PlanConfig Rig::Impl::plan_config(PixelType input, bool metrics) const {
    PlanConfig p;
    p.fusion = cfg->fusion;
    p.height = height;
    p.width = width;
    p.channels = 3;
    p.frames = int(cfg->sequence.size());
    p.sensors = int(sensors.size());
    p.input = input;
    p.want_fused = cfg->want_fused || !metrics;
    p.metrics = metrics ? cfg->metrics.with(Metric::BackgroundDiff,
                                            cfg->metrics.has(Metric::BackgroundDiff) && cfg->background_frames > 0)
                        : MetricSet{};
    if (metrics) p.skip = cfg->skip;  // the background means themselves are always fused
    if (metrics) p.cycles_in_flight = cfg->cycles_in_flight;
    return p;
}

// Every sensor still in step has delivered, and there is something to fuse
// (or nothing left that could deliver). A lost sensor may deliver again: while
// every sensor is lost the cycle waits for one to return (or for the cycle
// timeout) instead of returning at once, cycle after cycle.
bool Rig::Impl::cycle_ready() const {
    bool any_ready = false, any_alive = false;
    for (std::size_t i = 0; i < hub->slots.size(); ++i) {
        const rig::SensorSlot& slot = hub->slots[i];
        if (slot.failed) continue;
        any_alive = true;
        if (slot.lost) continue;
        if (!slot.ready.empty())
            any_ready = true;
        else if (!lagging[i] || numbered[i])
            return false;
    }
    return any_ready || !any_alive;
}

// Backgrounds that arrived since the last cycle are fused like frames (one
// submit for all of them) and become those sensors' reference for D.
void Rig::Impl::apply_new_backgrounds() {
    std::vector<std::vector<Image>> fresh(sensors.size()), deviations(sensors.size());
    bool any = false;
    {
        std::lock_guard lock(hub->mutex);
        for (std::size_t i = 0; i < sensors.size(); ++i) {
            rig::SensorSlot& slot = hub->slots[i];
            if (!slot.background_done || slot.background_applied || slot.background.empty()) continue;
            fresh[i] = slot.background;
            deviations[i] = slot.deviation;
            slot.background_applied = true;
            any = true;
        }
    }
    if (!any || !engine) return;
    if (!bg_engine) bg_engine = rig::make_engine(context, plan_config(PixelType::F32, false));
    const Image zero(height, width, 3);
    std::vector<FrameView> views;
    for (const auto& means : fresh)
        for (std::size_t k = 0; k < cfg->sequence.size(); ++k)
            views.push_back(FrameView::of(means.empty() ? zero : means[k]));
    bg_engine->run(views);
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        if (fresh[i].empty()) continue;
        engine->set_background(int(i), bg_engine->fused(int(i)));
        if (cfg->skip.policy == SkipPolicy::Off) continue;
        engine->set_skip_reference(int(i), SkipReference{fresh[i], deviations[i]});
        fill[i].clear();
        for (const Image& mean : fresh[i]) fill[i].push_back(io::to_8bit(mean));
        idle_metrics[i].reset();
        idle_image[i] = nullptr;
        std::lock_guard lock(hub->mutex);
        hub->slots[i].verdicts_from = hub->slots[i].judged;
    }
}

std::vector<FrameView> Rig::Impl::views_for(const std::vector<SensorCycle>& results) const {
    std::vector<FrameView> views;
    const std::size_t K = cfg->sequence.size();
    for (std::size_t i = 0; i < results.size(); ++i) {
        const std::vector<Frame>& frames = results[i].status == SensorStatus::Ok ? results[i].frames : last_good[i];
        for (std::size_t k = 0; k < K; ++k) {
            if (k < frames.size())
                views.push_back(frames[k].view());
            else if (!frames.empty() && k < fill[i].size())  // a watch cycle
                views.push_back(FrameView{fill[i][k].data(), height, width, 3, PixelType::U8});
            else
                views.push_back(FrameView{black.data(), height, width, 3, PixelType::U8});
        }
    }
    return views;
}

void Rig::Impl::stop_threads() {
    {
        std::lock_guard lock(hub->mutex);
        hub->stop = true;
    }
    hub->changed.notify_all();
    {
        // Waits out a background mean or callback in progress; none starts after.
        std::lock_guard work(hub->work_mutex);
        hub->model.reset();
    }
    std::unique_lock lock(hub->mutex);
    hub->changed.wait_until(lock, after(cfg->cycle_timeout_s), [&] {
        for (std::size_t i = 0; i < threads.size(); ++i)
            if (!hub->slots[i].exited) return false;
        return true;
    });
    for (std::size_t i = 0; i < threads.size(); ++i) {
        // A thread still inside a sensor call cannot be interrupted; it holds
        // its own references to everything it uses and exits when the call returns.
        if (hub->slots[i].exited)
            threads[i].join();
        else
            threads[i].detach();
    }
    threads.clear();
}

Rig::Rig(Context* context, RigConfig config, std::vector<RigSensor> sensors)
    : impl_(std::make_unique<Impl>(context, std::move(config), std::move(sensors))) {}

Rig::~Rig() { impl_->stop_threads(); }

// Waits until every sensor has its background or failed (or the start-up
// timeout); sensors still calibrating then are not waited for by cycles.
// Throws the sensors' errors when none got that far.
void Rig::Impl::await_startup() {
    std::unique_lock lock(hub->mutex);
    hub->changed.wait_until(lock, after(cfg->startup_timeout_s), [&] {
        for (const rig::SensorSlot& s : hub->slots)
            if (!s.failed && !s.background_done) return false;
        return true;
    });
    bool any_up = false;
    std::string errors;
    for (std::size_t i = 0; i < hub->slots.size(); ++i) {
        const rig::SensorSlot& s = hub->slots[i];
        any_up = any_up || s.background_done;
        if (s.failed) errors += (errors.empty() ? "" : "; ") + s.error;
        lagging[i] = !s.failed && !s.background_done;
    }
    if (any_up) return;
    if (errors.empty()) errors = "rig: no sensor calibrated within " + std::to_string(cfg->startup_timeout_s) + " s";
    throw Error(ErrorKind::Device, errors);
}

void Rig::start() {
    auto& im = *impl_;
    if (im.started) throw Error(ErrorKind::InvalidArgument, "rig: already started");
    im.started = true;
    for (std::size_t i = 0; i < im.sensors.size(); ++i)
        im.threads.emplace_back(rig::capture_main, rig::CaptureJob{i, im.sensors[i], im.cfg, im.hub});
    im.await_startup();
    im.apply_new_backgrounds();
}

// Takes the oldest cycle of every mailbox once the cycle is ready (or the
// timeout passed), and says what happened to each sensor.
void Rig::Impl::take_cycle(CycleResult& result) {
    std::unique_lock lock(hub->mutex);
    hub->changed.wait_until(lock, after(cfg->cycle_timeout_s), [&] { return cycle_ready(); });
    // Per origin, the earliest of its cycles a sensor has ready.
    std::map<std::uint64_t, std::uint64_t> earliest;
    auto origin_of = [](const rig::SensorSlot& slot) -> const Frame* {
        const Frame* f = first_ready_frame(slot);
        return f && f->origin != 0 ? f : nullptr;
    };
    for (const rig::SensorSlot& slot : hub->slots)
        if (const Frame* f = origin_of(slot)) {
            auto [it, fresh] = earliest.emplace(f->origin, f->origin_cycle);
            if (!fresh) it->second = std::min(it->second, f->origin_cycle);
        }
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        rig::SensorSlot& slot = hub->slots[i];
        SensorCycle& r = result.sensors[i];
        r.serial = slot.serial;
        const Frame* origin = origin_of(slot);
        if (const Frame* f = first_ready_frame(slot); f && (f->recorded_cycle >= 0 || origin)) numbered[i] = true;
        // Frames for a later cycle of their origin than another sensor's: kept for the next cycle.
        const bool ahead_of_origin = origin && origin->origin_cycle > earliest.at(origin->origin);
        if (!slot.ready.empty() && for_a_later_cycle(slot.ready.front(), result.cycle)) {
            r.status = SensorStatus::Timeout;
            r.error = slot.serial + ": no frames recorded for cycle " + std::to_string(result.cycle);
        } else if (ahead_of_origin) {
            r.status = SensorStatus::Timeout;
            r.error = slot.serial + ": no frames of its origin's cycle " + std::to_string(earliest.at(origin->origin)) +
                      " (its next are of cycle " + std::to_string(origin->origin_cycle) + ")";
        } else if (!slot.ready.empty()) {
            r.frames = std::move(slot.ready.front());
            slot.ready.pop_front();
        } else if (slot.failed || slot.lost) {
            r.status = slot.failed ? SensorStatus::Failed : *slot.lost;
            r.error = slot.error;
        } else {
            r.status = SensorStatus::Timeout;
            r.error = slot.serial + ": no frames within " + std::to_string(cfg->cycle_timeout_s) + " s (cycle " +
                      std::to_string(result.cycle) + ")";
        }
    }
    lock.unlock();
    hub->changed.notify_all();  // mailboxes are free again
}

CycleResult Rig::Impl::start_cycle() {
    CycleResult result;
    result.cycle = cycle++;
    result.sensors.resize(sensors.size());
    const auto wait_start = WallClock::now();
    take_cycle(result);
    result.capture_wait_s = seconds_since(wait_start);
    apply_new_backgrounds();
    const auto fuse_start = WallClock::now();
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        const bool ok = result.sensors[i].status == SensorStatus::Ok;
        if (ok && engine) last_good[i] = result.sensors[i].frames;  // what a late sensor's slot is fused from
        lagging[i] = !ok && !numbered[i];
    }
    if (engine) engine->submit(views_for(result.sensors));
    result.fuse_s = seconds_since(fuse_start);
    return result;
}

void Rig::Impl::report(CycleResult& result) {
    if (!engine) return;  // fusion off: the frames are the result
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        SensorCycle& r = result.sensors[i];
        if (r.status != SensorStatus::Ok) continue;
        r.skip = engine->skip_outcome(int(i));
        r.watch = r.frames.size() < cfg->sequence.size();
        if (r.watch && !r.skip.idle && idle_metrics[i]) {
            // The frame changed, but one setting is no cycle to fuse: the
            // result stays the fused background until the next cycle, which
            // captures the whole sequence.
            r.skip.idle = true;
            r.skip.fused_fraction = 0;
            r.metrics = *idle_metrics[i];
            r.fused = idle_image[i];
        } else {
            r.metrics = engine->metrics(int(i));
            if (cfg->want_fused) r.fused = &engine->fused(int(i));
            if (r.skip.idle) {
                idle_metrics[i] = r.metrics;
                idle_image[i] = r.fused;
            }
        }
        std::lock_guard lock(hub->mutex);
        rig::SensorSlot& slot = hub->slots[i];
        slot.idle_verdicts[slot.judged % 4] = r.skip.idle && r.skip.changed_fraction == 0;
        ++slot.judged;
    }
    hub->changed.notify_all();
}

// One round trip: take cycle c, fuse it, return it. Two cycles in flight:
// cycle c was submitted by the call before; take and submit c + 1, then
// collect c, so the device fuses c + 1 while the caller handles c.
CycleResult Rig::next() {
    auto& im = *impl_;
    if (!im.started) throw Error(ErrorKind::InvalidArgument, "rig: next() before start()");
    if (im.engine && im.engine->cycles_in_flight() > 1 && !im.ahead) im.ahead = im.start_cycle();
    CycleResult result = im.ahead ? std::move(*im.ahead) : im.start_cycle();
    if (im.ahead) im.ahead = im.start_cycle();
    const auto collect_start = WallClock::now();
    if (im.engine) im.engine->collect();
    result.fuse_s += seconds_since(collect_start);
    im.report(result);
    return result;
}

std::size_t Rig::sensors() const { return impl_->sensors.size(); }

std::string Rig::serial(std::size_t sensor) const { return impl_->hub->slots.at(sensor).serial; }

std::optional<SwitchTiming> Rig::timing(std::size_t sensor) const {
    std::lock_guard lock(impl_->hub->mutex);
    return impl_->hub->slots.at(sensor).timing;
}

std::string Rig::switch_scheduling(std::size_t sensor) const {
    std::lock_guard lock(impl_->hub->mutex);
    return impl_->hub->slots.at(sensor).switch_scheduling;
}

FusionWindow Rig::window() const { return impl_->cfg->window; }

std::optional<double> Rig::window_bound(std::size_t sensor) const {
    const std::optional<SwitchTiming> t = timing(sensor);
    if (!t) return std::nullopt;
    return vkfuse::window_bound(*t, impl_->cfg->sequence.size());
}

std::uint64_t Rig::windows_held(std::size_t sensor) const {
    std::lock_guard lock(impl_->hub->mutex);
    return impl_->hub->slots.at(sensor).windows_held;
}

bool Rig::all_failed() const {
    // Two cycles in flight: a cycle taken ahead with a sensor's frames in it
    // is still to be returned.
    if (impl_->ahead)
        for (const SensorCycle& s : impl_->ahead->sensors)
            if (s.status == SensorStatus::Ok) return false;
    std::lock_guard lock(impl_->hub->mutex);
    for (const rig::SensorSlot& s : impl_->hub->slots)
        if (!s.failed || !s.ready.empty()) return false;  // a cycle delivered before failing still counts
    return true;
}

std::uint64_t Rig::submits() const { return impl_->engine ? impl_->engine->submits() : 0; }

int Rig::cycles_in_flight() const { return impl_->engine ? impl_->engine->cycles_in_flight() : 1; }

double SensorCycle::newest_timestamp() const { return vkfuse::newest_timestamp(frames); }

double SensorCycle::window_span_s() const { return window_span(frames); }

std::string_view to_string(SensorStatus status) {
    switch (status) {
        case SensorStatus::Ok: return "ok";
        case SensorStatus::Timeout: return "timeout";
        case SensorStatus::Failed: return "failed";
    }
    return "?";
}

}  // namespace vkfuse

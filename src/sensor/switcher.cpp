// Switcher: frames lit entirely by requested settings, judged by timing (a
// live sensor) or by label (a recorded dataset). See include/vkfuse/sensor/switching.hpp.
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "sensor/realtime_section.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse {
namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();
// How often one slot of a cycle may be requested before the sensor is declared
// unable to deliver it (a frame missed its window every time).
constexpr int kMaxAttempts = 8;
// Frames a labelled sensor may deliver with another label before giving up.
constexpr int kMaxForeignFrames = 64;
// Window ends are computed by adding and subtracting the same timing terms;
// a frame exactly on the end must not fall out by a rounding error. A
// microsecond is far below any margin the calibration keeps.
constexpr double kRounding = 1e-6;

// A request whose frame has not arrived yet. Its window of acceptable frame
// timestamps is [first_lit(time), window_end]; window_end stays open until the
// next request is made, which fixes when the next switch can land.
struct Pending {
    std::uint64_t cycle = 0;
    std::size_t slot = 0;
    double time = 0;
    double window_end = kNever;
};

struct Key {
    std::uint64_t cycle = 0;
    std::size_t slot = 0;
    auto operator<=>(const Key&) const = default;
};

}  // namespace

struct Switcher::Impl {
    Sensor& sensor;
    std::shared_ptr<Clock> clock;  // null when judging by label
    SwitchTiming timing;
    std::string serial;
    std::uint64_t grabbed = 0, requests = 0;
    int switch_priority = 0;  // SCHED_FIFO around each timed request; 0: none

    // Timing-mode scheduler state, carried across cycles so the first request
    // of a cycle can overlap the last frame of the one before.
    IlluminationSequence sequence;
    bool have_frame = false;
    double last_ts = 0;
    double planned = -kNever;  // earliest time of the next request
    std::deque<Pending> pending;
    std::deque<Key> retries;
    std::map<Key, int> attempts;
    std::map<std::uint64_t, std::vector<std::optional<Frame>>> cycles;
    std::uint64_t next_to_return = 0;
    Key next_to_request;
    // Sliding windows: the newest frame of each slot, and which slot of cycle
    // next_to_return enters next.
    std::vector<std::optional<Frame>> newest;
    std::size_t entering = 0;
    std::uint64_t held = 0;
    // The setting requested last and when it lights whole frames from: a
    // capture under the setting already lit waits for no switch.
    std::optional<Illumination> lit;
    double lit_from = 0;

    Impl(Sensor& s, std::shared_ptr<Clock> c, const SwitchTiming& t)
        : sensor(s), clock(std::move(c)), timing(t), serial(s.info().serial) {}

    bool by_label() const { return !clock; }

    Frame grab() {
        ++grabbed;
        return sensor.grab();
    }
    double request(const Illumination& setting) {
        const double t = clock ? clock->now() : 0.0;
        sensor.set_illumination(setting);
        ++requests;
        if (clock) {
            lit = setting;
            lit_from = timing.first_lit(t);
        }
        return t;
    }
    bool labelled_otherwise(const Frame& f, const Illumination& setting) const {
        return f.illumination && *f.illumination != setting;
    }

    void reset(const IlluminationSequence& seq) {
        sequence = seq;
        pending.clear();
        retries.clear();
        attempts.clear();
        cycles.clear();
        planned = -kNever;
        next_to_request = {next_to_return, 0};
        newest.assign(seq.size(), std::nullopt);
        entering = 0;
    }

    std::vector<Frame> capture_by_label(const Illumination& setting, int n);
    std::vector<Frame> capture_by_timing(const Illumination& setting, int n);
    std::vector<Frame> cycle_by_label();
    std::vector<Frame> cycle_by_timing();
    std::vector<Frame> window_by_timing();

    // Timing-mode steps.
    std::optional<Key> next_request_key() const;
    void make_request(const Key& key);
    void grab_and_place();
    double predicted_frame(double not_before) const;
    bool cycle_complete(std::uint64_t cycle) const;
    bool in_hand(std::uint64_t cycle, std::size_t slot) const;
    void step();
    void cycle_returned();
};

std::vector<Frame> Switcher::Impl::capture_by_label(const Illumination& setting, int n) {
    request(setting);
    std::vector<Frame> out;
    int foreign = 0;
    while (int(out.size()) < n) {
        Frame f = grab();
        if (!f.illumination)
            throw Error(ErrorKind::InvalidArgument,
                        serial + ": frame " + std::to_string(f.index) +
                            " carries no illumination; judging by label needs a recorded dataset");
        if (*f.illumination == setting) {
            out.push_back(std::move(f));
        } else if (++foreign > kMaxForeignFrames) {
            throw Error(ErrorKind::Device, serial + ": no frame lit by " + setting.to_string() + " among the next " +
                                               std::to_string(kMaxForeignFrames) + " frames");
        }
    }
    return out;
}

std::vector<Frame> Switcher::Impl::capture_by_timing(const Illumination& setting, int n) {
    reset(sequence);  // a capture interrupts any cycle in progress
    const double ready = lit && *lit == setting ? lit_from : timing.first_lit(request(setting));
    std::vector<Frame> out;
    while (int(out.size()) < n) {
        Frame f = grab();
        have_frame = true;
        last_ts = f.timestamp;
        if (f.timestamp >= ready && !labelled_otherwise(f, setting)) out.push_back(std::move(f));
    }
    return out;
}

std::vector<Frame> Switcher::Impl::cycle_by_label() {
    std::vector<Frame> out;
    for (const Illumination& setting : sequence) out.push_back(std::move(capture_by_label(setting, 1).front()));
    return out;
}

// Retries first, then the next slot in order. Requests run ahead of the cycle
// being assembled by as many cycles as the LED latency spans (a switch
// requested now lands that much later), plus the one whose first request
// overlaps this one's end.
std::optional<Key> Switcher::Impl::next_request_key() const {
    if (!retries.empty()) return retries.front();
    const double cycle_s = double(sequence.size()) * timing.frame_period;
    const auto ahead = std::uint64_t(std::ceil(timing.latency_max / cycle_s)) + 1;
    if (next_to_request.cycle > next_to_return + ahead) return std::nullopt;
    return next_to_request;
}

// The timestamp of the first frame at or after not_before, predicted from the
// last frame and the frame period.
double Switcher::Impl::predicted_frame(double not_before) const {
    if (!have_frame) return not_before;
    const double periods = std::max(1.0, std::ceil((not_before - last_ts) / timing.frame_period));
    return last_ts + periods * timing.frame_period;
}

void Switcher::Impl::make_request(const Key& key) {
    if (!retries.empty() && retries.front() == key) {
        retries.pop_front();
    } else if (++next_to_request.slot == sequence.size()) {
        next_to_request = {next_to_request.cycle + 1, 0};
    }
    if (++attempts[key] > kMaxAttempts)
        throw Error(ErrorKind::Device, serial + ": no frame lit entirely by " + sequence[key.slot].to_string() +
                                           " after " + std::to_string(kMaxAttempts) +
                                           " requests (frames late or dropped)");
    double t = 0;
    {
        const sensor::RealtimeSection punctual(switch_priority);
        clock->wait_until(planned);
        t = request(sequence[key.slot]);
    }
    // The previous request's frame must finish before this switch can land.
    for (Pending& p : pending)
        if (p.window_end == kNever) p.window_end = timing.last_untouched(t);
    pending.push_back({key.cycle, key.slot, t, kNever});
    // Leave room for the predicted frame to come up to `jitter` late.
    planned = timing.next_request(predicted_frame(timing.first_lit(t)) + timing.jitter);
}

void Switcher::Impl::grab_and_place() {
    Frame f = grab();
    have_frame = true;
    last_ts = f.timestamp;
    for (auto it = pending.begin(); it != pending.end();) {
        if (f.timestamp > it->window_end + kRounding) {  // its window closed empty: ask again
            retries.push_back({it->cycle, it->slot});
            it = pending.erase(it);
            continue;
        }
        if (f.timestamp >= timing.first_lit(it->time) && !labelled_otherwise(f, sequence[it->slot])) {
            // The next request, if not made yet, must wait for this frame's last row.
            if (it->window_end == kNever) planned = std::max(planned, timing.next_request(f.timestamp));
            auto& slots = cycles[it->cycle];
            slots.resize(sequence.size());
            slots[it->slot] = std::move(f);
            pending.erase(it);
            return;
        }
        ++it;
    }
}

bool Switcher::Impl::cycle_complete(std::uint64_t cycle) const {
    auto it = cycles.find(cycle);
    if (it == cycles.end()) return false;
    for (const auto& slot : it->second)
        if (!slot) return false;
    return true;
}

bool Switcher::Impl::in_hand(std::uint64_t cycle, std::size_t slot) const {
    auto it = cycles.find(cycle);
    return it != cycles.end() && slot < it->second.size() && it->second[slot].has_value();
}

// One move of the scheduler: a request is made at `planned` whenever the next
// frame will not be in hand by then (frames arrive `delivery` after their
// timestamp); otherwise the frame is grabbed first. So the thread does not
// sit in grab() while a switch is due.
void Switcher::Impl::step() {
    const std::optional<Key> key = next_request_key();
    const double in_hand_by = have_frame ? last_ts + timing.frame_period + timing.delivery : kNever;
    if (key && (pending.empty() || planned <= in_hand_by)) {
        make_request(*key);
    } else if (pending.empty()) {
        throw Error(ErrorKind::Device, serial + ": switch scheduler has nothing to wait for");  // unreachable
    } else {
        grab_and_place();
    }
}

// Cycle next_to_return has been handed out: requests may run further ahead.
void Switcher::Impl::cycle_returned() {
    cycles.erase(next_to_return);
    for (auto it = attempts.begin(); it != attempts.end();)
        it = it->first.cycle == next_to_return ? attempts.erase(it) : std::next(it);
    ++next_to_return;
}

std::vector<Frame> Switcher::Impl::cycle_by_timing() {
    if (!have_frame) grab_and_place();  // learn the frame grid before predicting frames
    while (!cycle_complete(next_to_return)) step();
    std::vector<Frame> out;
    for (auto& slot : cycles[next_to_return]) out.push_back(std::move(*slot));
    cycle_returned();
    return out;
}

// The same schedule as cycle_by_timing, its frames taken into the window one
// slot at a time in sequence order.
std::vector<Frame> Switcher::Impl::window_by_timing() {
    if (!have_frame) grab_and_place();
    const double bound = window_bound(timing, sequence.size());
    for (;;) {
        while (!in_hand(next_to_return, entering)) step();
        newest[entering] = std::move(*cycles[next_to_return][entering]);
        if (++entering == sequence.size()) {
            cycle_returned();
            entering = 0;
        }
        if (!std::all_of(newest.begin(), newest.end(), [](const auto& f) { return f.has_value(); })) continue;
        std::vector<Frame> out;
        for (const auto& f : newest) out.push_back(*f);
        if (window_span(out) <= bound + kRounding) return out;
        ++held;
    }
}

std::string_view to_string(FusionWindow window) {
    return window == FusionWindow::Sliding ? "sliding" : "cycle";
}

FusionWindow parse_fusion_window(std::string_view name, std::string_view what) {
    for (FusionWindow w : {FusionWindow::Cycle, FusionWindow::Sliding})
        if (name == to_string(w)) return w;
    throw Error(ErrorKind::InvalidArgument, std::string(what) + " " + std::string(name) + ": expected cycle or sliding");
}

double newest_timestamp(std::span<const Frame> frames) {
    double t = frames.empty() ? 0.0 : frames.front().timestamp;
    for (const Frame& f : frames) t = std::max(t, f.timestamp);
    return t;
}

double window_span(std::span<const Frame> frames) {
    const double newest = newest_timestamp(frames);
    double oldest = newest;
    for (const Frame& f : frames) oldest = std::min(oldest, f.timestamp);
    return newest - oldest;
}

double window_bound(const SwitchTiming& timing, std::size_t settings) {
    // A switch is requested `clearance` (and `jitter`, for a late frame)
    // after the last frame of the setting before; its first whole frame is
    // the first on the frame grid `latency_max` after the request.
    const double gap = timing.jitter + timing.clearance + timing.latency_max;
    const double slot = timing.frame_period * std::max(1.0, std::ceil(gap / timing.frame_period - kRounding));
    return double(settings) * slot + timing.latency_max;
}

std::string Switcher::set_switch_priority(int priority) {
    if (priority < 0 || priority > 99)
        throw Error(ErrorKind::InvalidArgument, impl_->serial + ": switch priority " + std::to_string(priority) + " (expected 0..99)");
    impl_->switch_priority = 0;
    if (priority == 0) return "normal";
    const std::string refused = sensor::realtime_refusal(priority);
    if (!refused.empty()) return "normal (fifo " + std::to_string(priority) + " refused: " + refused + ")";
    impl_->switch_priority = priority;
    return "fifo " + std::to_string(priority);
}

Switcher::Switcher(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Switcher::Switcher(Sensor& sensor, std::shared_ptr<Clock> clock, const SwitchTiming& timing) {
    if (!clock)
        throw Error(ErrorKind::InvalidArgument, sensor.info().serial + ": judging by timing needs the sensor's clock");
    if (!(timing.frame_period > 0) || !std::isfinite(timing.latency_max) || !std::isfinite(timing.clearance))
        throw Error(ErrorKind::InvalidArgument, sensor.info().serial + ": switch timing not measured");
    impl_ = std::make_unique<Impl>(sensor, std::move(clock), timing);
}

Switcher Switcher::labelled(Sensor& sensor) {
    return Switcher(std::make_unique<Impl>(sensor, nullptr, SwitchTiming{}));
}

Switcher::~Switcher() = default;
Switcher::Switcher(Switcher&&) noexcept = default;
Switcher& Switcher::operator=(Switcher&&) noexcept = default;

std::vector<Frame> Switcher::capture(const Illumination& setting, int n) {
    return impl_->by_label() ? impl_->capture_by_label(setting, n) : impl_->capture_by_timing(setting, n);
}

std::vector<Frame> Switcher::next_cycle(const IlluminationSequence& sequence) {
    if (sequence.empty()) throw Error(ErrorKind::InvalidArgument, impl_->serial + ": empty illumination sequence");
    if (sequence != impl_->sequence) impl_->reset(sequence);
    return impl_->by_label() ? impl_->cycle_by_label() : impl_->cycle_by_timing();
}

std::vector<Frame> Switcher::next_window(const IlluminationSequence& sequence) {
    if (sequence.empty()) throw Error(ErrorKind::InvalidArgument, impl_->serial + ": empty illumination sequence");
    if (impl_->by_label())
        throw Error(ErrorKind::InvalidArgument,
                    impl_->serial + ": sliding windows are formed by timing; recorded frames are replayed as recorded");
    if (sequence != impl_->sequence) impl_->reset(sequence);
    return impl_->window_by_timing();
}

std::uint64_t Switcher::windows_held() const { return impl_->held; }

std::uint64_t Switcher::frames_grabbed() const { return impl_->grabbed; }
std::uint64_t Switcher::requests_made() const { return impl_->requests; }

}  // namespace vkfuse

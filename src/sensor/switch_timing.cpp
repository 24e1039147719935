// measure_switch_timing(): LED latency and rolling-shutter frame span from
// frame timestamps (include/vkfuse/sensor/switching.hpp).
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>

#include "sensor/realtime_section.hpp"
#include "sensor/row_profile.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse {
namespace {

using sensor::Lighting;
using sensor::RowProfile;

// Row means closer than this (8-bit levels) count as the same steady image.
constexpr double kSteadyLevels = 2.0;
// A switch is given up on only after this many frames as well as the
// timeout: a host too slow to take every frame sees few of them per second.
constexpr int kMinFramesBeforeGivingUp = 12;
// Rows the switch moves less than this take no part in judging frames.
constexpr double kMinChangeLevels = 8.0;
// Calibration needs a clear majority of rows to respond to the LEDs.
constexpr double kMinResponsiveRows = 0.25;

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// Grabs frames and keeps what the timing needs: the spacing of timestamps and
// how long after its timestamp each frame was in hand.
class Observer {
public:
    Observer(Sensor& sensor, Clock& clock) : sensor_(sensor), clock_(clock), serial_(sensor.info().serial) {}

    Frame grab() {
        Frame f = sensor_.grab();
        deliveries_.push_back(clock_.now() - f.timestamp);
        // Per frame of the sensor's counter: a host too slow to take every
        // frame still measures the period, not the gaps between its grabs.
        if (have_last_ && f.index > last_index_) {
            const double per_frame = (f.timestamp - last_ts_) / double(f.index - last_index_);
            spacings_.push_back(per_frame);
            if (f.index == last_index_ + 1) neighbours_.push_back(per_frame);
        }
        last_ts_ = f.timestamp;
        last_index_ = f.index;
        have_last_ = true;
        return f;
    }
    double request(const Illumination& setting) {
        const double t = clock_.now();
        sensor_.set_illumination(setting);
        return t;
    }
    Clock& clock() { return clock_; }
    double last_ts() const { return last_ts_; }
    const std::string& serial() const { return serial_; }

    // Median spacing per frame and the largest deviation of the spacing of
    // two consecutive frames from it.
    std::pair<double, double> period_and_jitter(double fallback) const {
        if (spacings_.empty()) return {fallback, 0.0};
        const double period = median(spacings_);
        double jitter = 0;
        for (double d : neighbours_) jitter = std::max(jitter, std::abs(d - period));
        return {period, jitter};
    }
    double delivery() const { return deliveries_.empty() ? 0.0 : median(deliveries_); }

private:
    Sensor& sensor_;
    Clock& clock_;
    std::string serial_;
    std::vector<double> spacings_, neighbours_, deliveries_;
    double last_ts_ = 0;
    std::uint64_t last_index_ = 0;
    bool have_last_ = false;
};

// Requests setting, then returns the steady row profile once settle_s has
// passed and three frames in a row agree.
RowProfile settle(Observer& obs, const Illumination& setting, const SwitchCalibration& opt) {
    const double t0 = obs.request(setting);
    std::deque<RowProfile> recent;
    for (int seen = 1;; ++seen) {
        const Frame f = obs.grab();
        if (f.timestamp - t0 > opt.settle_s + opt.timeout_s && seen > kMinFramesBeforeGivingUp)
            throw Error(ErrorKind::Device, obs.serial() + ": frames do not settle within " +
                                               std::to_string(opt.settle_s + opt.timeout_s) +
                                               " s after switching the LEDs to " + setting.to_string());
        recent.push_back(sensor::row_profile(f));
        if (recent.size() > 3) recent.pop_front();
        if (f.timestamp - t0 < opt.settle_s || recent.size() < 3) continue;
        if (sensor::max_row_difference(recent[0], recent[1]) <= kSteadyLevels &&
            sensor::max_row_difference(recent[1], recent[2]) <= kSteadyLevels)
            return recent.back();
    }
}

// What the switches of one direction showed, before margins: the tightest
// bound each switch gave.
struct Bounds {
    double latency = std::numeric_limits<double>::infinity();    // first new frame - request
    double clearance = std::numeric_limits<double>::infinity();  // request - last entirely old frame
};

// One switch: request `to` at a chosen phase, grab until the first frame lit
// entirely by it (matching its steady profile). That frame bounds the latency;
// the last frame still entirely old, which ended before the switch landed,
// bounds the clearance. The phase is a fraction of the frame period after a
// frame's timestamp, on the grid of the last frame grabbed, so that however
// late a busy host lets this thread have that frame, the phases land where
// they were spread (bunched phases give looser bounds than the sensor's).
void observe_switch(Observer& obs, const sensor::LightingJudge& judge, const Illumination& to, double phase,
                    double period, const SwitchCalibration& opt, Bounds& b) {
    double last_old_ts = 0, t = 0;
    {
        const sensor::RealtimeSection punctual(opt.request_priority);
        const double now = obs.clock().now(), grid = obs.last_ts();
        double at = grid + (std::floor((now - grid) / period) + phase) * period;
        if (at < now) at += period;
        obs.clock().wait_until(at);
        last_old_ts = obs.last_ts();  // the settled frame before the request
        t = obs.request(to);
    }
    for (int seen = 1;; ++seen) {
        const Frame f = obs.grab();
        if (f.timestamp - t > opt.timeout_s && seen > kMinFramesBeforeGivingUp)
            throw Error(ErrorKind::Device, obs.serial() + ": LEDs did not switch to " + to.to_string() + " within " +
                                               std::to_string(opt.timeout_s) + " s");
        const Lighting lit = judge.judge(sensor::row_profile(f));
        if (lit == Lighting::New) {
            b.latency = std::min(b.latency, f.timestamp - t);
            b.clearance = std::min(b.clearance, t - last_old_ts);
            return;
        }
        if (lit == Lighting::Old) last_old_ts = f.timestamp;
    }
}

Illumination uniform(const LedLayout& leds, int level) {
    return Illumination(std::vector<int>(std::size_t(leds.channels), level));
}

}  // namespace

SwitchTiming measure_switch_timing(Sensor& sensor, Clock& clock, const SwitchCalibration& opt) {
    const SensorInfo info = sensor.info();
    if (opt.trials < 2) throw Error(ErrorKind::InvalidArgument, info.serial + ": switch calibration needs trials >= 2");
    const Illumination off = uniform(info.leds, 0), on = uniform(info.leds, info.leds.max_level);
    Observer obs(sensor, clock);
    const RowProfile dark = settle(obs, off, opt);
    const RowProfile bright = settle(obs, on, opt);
    const sensor::LightingJudge to_off(bright, dark, opt.tolerance, kMinChangeLevels);
    const sensor::LightingJudge to_on(dark, bright, opt.tolerance, kMinChangeLevels);
    if (to_on.responsive_fraction() < kMinResponsiveRows)
        throw Error(ErrorKind::Device, info.serial + ": frames barely change between LEDs " + off.to_string() +
                                           " and " + on.to_string() + "; cannot measure the switch latency");
    const double nominal = info.fps > 0 ? 1.0 / info.fps : 1.0 / 30.0;
    Bounds to_dark, to_bright;
    for (int i = 0; i < opt.trials; ++i) {
        // Golden-ratio phases spread each direction's requests evenly over a
        // frame period, so every switch cuts the bounds at a different place.
        const double phase = std::fmod(double(i / 2) * 0.6180339887498949, 1.0);
        const double period = obs.period_and_jitter(nominal).first;
        const bool going_dark = i % 2 == 0;  // the LEDs are on after settling
        observe_switch(obs, going_dark ? to_off : to_on, going_dark ? off : on, phase, period, opt,
                       going_dark ? to_dark : to_bright);
    }
    SwitchTiming t;
    std::tie(t.frame_period, t.jitter) = obs.period_and_jitter(nominal);
    t.delivery = obs.delivery();
    t.trials = opt.trials;
    // A row judged unchanged may have seen up to `tolerance` of the other
    // setting: widen both bounds by that share of a frame period.
    const double margin = opt.tolerance * t.frame_period;
    t.latency_max = std::max(to_dark.latency, to_bright.latency) + margin;
    t.clearance = std::max(to_dark.clearance, to_bright.clearance) + margin;
    return t;
}

}  // namespace vkfuse

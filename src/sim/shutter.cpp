// LED timeline and rolling shutter (sim/shutter.hpp).
#include "sim/shutter.hpp"

#include <algorithm>

#include "sim/led.hpp"

namespace vkfuse::sim {
namespace {

// The DIGIT's sensor reads its rows out over most of the frame period (the
// rest is vertical blanking), and in a bright gel its auto exposure settles
// near half the period.
constexpr double kReadoutFraction = 0.9;
constexpr double kExposureFraction = 0.5;

}  // namespace

ShutterTiming ShutterTiming::for_stream(double fps, int rows) {
    const double period = 1.0 / fps;
    return {period, kReadoutFraction * period / rows, kExposureFraction * period, rows};
}

void LedTimeline::change(double at, const Illumination& setting) {
    while (!changes_.empty() && changes_.back().first >= at) changes_.pop_back();
    changes_.emplace_back(at, setting);
}

std::array<double, 3> LedTimeline::mean_drive(double t0, double t1, int max_level) const {
    std::array<double, 3> drive{};
    const Illumination* current = &initial_;
    double from = t0;
    auto add = [&](double until) {
        const double w = (std::min(until, t1) - from) / (t1 - t0);
        if (w > 0)
            for (int k = 0; k < 3; ++k) drive[std::size_t(k)] += w * led_drive(current->level(k), max_level);
    };
    for (const auto& [at, setting] : changes_) {
        if (at >= t1) break;
        if (at > from) {
            add(at);
            from = at;
        }
        current = &setting;
    }
    add(t1);
    return drive;
}

std::vector<Illumination> LedTimeline::settings_during(double t0, double t1) const {
    std::vector<Illumination> out;
    const Illumination* current = &initial_;
    auto note = [&](const Illumination& s) {
        if (out.empty() || !(out.back() == s)) out.push_back(s);
    };
    for (const auto& [at, setting] : changes_) {
        if (at >= t1) break;
        if (at > t0) note(*current);  // `current` lit [max(t0, previous change), at)
        current = &setting;
    }
    note(*current);
    return out;
}

void LedTimeline::forget_before(double t) {
    // Keep the last change at or before t: it is what is in effect at t.
    auto first_after = std::find_if(changes_.begin(), changes_.end(), [t](const auto& c) { return c.first > t; });
    if (first_after == changes_.begin()) return;
    initial_ = std::prev(first_after)->second;
    changes_.erase(changes_.begin(), first_after);
}

}  // namespace vkfuse::sim

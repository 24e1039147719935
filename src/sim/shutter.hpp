// sim/shutter.hpp - when light reaches which row: the LED switching
// timeline and the rolling shutter that samples it.
#pragma once
#include <array>
#include <utility>
#include <vector>

#include "vkfuse/illumination.hpp"

namespace vkfuse::sim {

// Rolling shutter of one stream: row r of a frame starting at t is exposed
// during [t + r * row_time, t + r * row_time + exposure].
struct ShutterTiming {
    double frame_period = 0;
    double row_time = 0;
    double nominal_exposure = 0;
    int rows = 0;

    // From the first row's start to the last row's end.
    double span(double exposure) const { return (rows - 1) * row_time + exposure; }
    static ShutterTiming for_stream(double fps, int rows);
};

// The LED settings over time: an initial one, then each requested setting
// from the moment it takes effect.
class LedTimeline {
public:
    explicit LedTimeline(Illumination initial) : initial_(std::move(initial)) {}

    // Effective times must not decrease (requests are made in time order with
    // one fixed latency); a change at the same time as another replaces it.
    void change(double at, const Illumination& setting);
    // Each LED channel's drive (0..1) averaged over [t0, t1]: what a row
    // exposed over that interval integrates.
    std::array<double, 3> mean_drive(double t0, double t1, int max_level) const;
    // The distinct settings in effect for some positive time within [t0, t1],
    // in time order.
    std::vector<Illumination> settings_during(double t0, double t1) const;
    // Drops changes that can no longer matter to anything exposed from t on.
    void forget_before(double t);

private:
    Illumination initial_;
    std::vector<std::pair<double, Illumination>> changes_;  // sorted by time
};

}  // namespace vkfuse::sim

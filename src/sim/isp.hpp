// sim/isp.hpp - the camera's own image processor: auto exposure and
// auto white balance, as the DIGIT's camera module runs them while streaming.
//
// Why they matter here: a frame lit by the green LED alone gets about half the
// light of the white frame and almost nothing in red and blue. The ISP meters
// every frame and, over the next few frames, lifts exposure (then gain) back
// to its brightness target and the red and blue gains toward grey, within its
// limits. Those few frames of convergence, after the LED's own latency, are
// why frames taken soon after a switch are unusable.
#pragma once
#include <cstddef>
#include <cstdint>

#include "sim/camera.hpp"

namespace vkfuse::sim {

struct IspLimits {
    double max_exposure_scale = 1.9;   // exposure up to 95% of the frame period (nominal: 50%)
    double min_exposure_scale = 0.02;
    double max_analog_gain = 4;        // the module's gain ceiling
    double max_white_balance = 4;      // red/blue gain range 1/4 .. 4 relative to green
    double step = 0.8;                 // fraction of the (log) error corrected per frame
};

// What the ISP steers to: mean luma, and the red/green and blue/green ratios
// of channel means it takes for neutral ("grey world" with the camera's own
// white point).
struct IspTarget {
    double luma = 0;
    double red_to_green = 1;
    double blue_to_green = 1;
};

class Isp {
public:
    // enabled false: a fixed nominal readout (exposure scale 1, unity gains).
    Isp(IspTarget target, bool enabled, IspLimits limits = {}) : target_(target), enabled_(enabled), limits_(limits) {}

    const Readout& readout() const { return readout_; }
    // Meters a frame just read out (8-bit HWC) and sets the next readout.
    void meter(const std::uint8_t* frame, std::size_t pixels);

private:
    void auto_exposure(double luma);
    void auto_white_balance(double red, double green, double blue);

    IspTarget target_;
    bool enabled_;
    IspLimits limits_;
    Readout readout_;
};

}  // namespace vkfuse::sim

// Auto exposure and auto white balance (sim/isp.hpp).
#include "sim/isp.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vkfuse::sim {
namespace {

// Below this green mean (DN) the frame is too dark to judge its colour.
constexpr double kDarkForWhiteBalance = 4.0;
// Luma floor for metering a black frame (avoids dividing by zero).
constexpr double kDarkLuma = 0.5;

}  // namespace

void Isp::meter(const std::uint8_t* frame, std::size_t pixels) {
    if (!enabled_ || pixels == 0) return;
    double sum[3] = {0, 0, 0};
    for (std::size_t i = 0; i < pixels * 3; ++i) sum[i % 3] += frame[i];
    const double r = sum[0] / double(pixels), g = sum[1] / double(pixels), b = sum[2] / double(pixels);
    auto_exposure(0.299 * r + 0.587 * g + 0.114 * b);
    auto_white_balance(r, g, b);
}

void Isp::auto_exposure(double luma) {
    // The total exposure (time x gain) moves a fixed fraction of the way, in
    // log terms, toward what would hit the target; time first, then gain.
    const double total = readout_.exposure_scale * readout_.analog_gain *
                         std::pow(target_.luma / std::max(luma, kDarkLuma), limits_.step);
    readout_.exposure_scale = std::clamp(total, limits_.min_exposure_scale, limits_.max_exposure_scale);
    readout_.analog_gain = std::clamp(total / readout_.exposure_scale, 1.0, limits_.max_analog_gain);
}

void Isp::auto_white_balance(double red, double green, double blue) {
    if (green < kDarkForWhiteBalance) return;
    // Grey world: pull the red and blue means toward the white point's ratios to green.
    for (auto [c, ratio] : {std::pair{0, red / green / target_.red_to_green}, std::pair{2, blue / green / target_.blue_to_green}}) {
        const double error = std::log(std::max(ratio, 1e-3));
        double& wb = readout_.white_balance[std::size_t(c)];
        wb = std::clamp(wb * std::exp(-limits_.step * error), 1.0 / limits_.max_white_balance, limits_.max_white_balance);
    }
}

}  // namespace vkfuse::sim

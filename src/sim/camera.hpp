// sim/camera.hpp - the image sensor: integrates each row's light,
// adds shot and read noise, amplifies, quantises to 8 bits and clips.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "sim/optics.hpp"
#include "sim/rng.hpp"

namespace vkfuse::sim {

struct CameraNoise {
    // Photo-electrons per DN at unity gain: shot noise has variance signal / gain in DN^2.
    double electrons_per_dn = 100;
    // Read (and dark) noise, DN at unity gain, signal-independent.
    double read_noise_dn = 0.5;

    // Chosen so that the simulated background shows the fine-scale noise of
    // the real DIGIT frame (tests/data/digit_bg_tacto.png): about 0.7-0.9 DN
    // around 100 DN after the camera's own processing.
    static CameraNoise digit() { return {}; }
};

// How one frame is read out (set by the ISP, see sim/isp.hpp).
struct Readout {
    double exposure_scale = 1;                 // exposure / nominal exposure: more light collected
    double analog_gain = 1;                    // amplifies signal and noise alike
    std::array<double, 3> white_balance{1, 1, 1};  // per-channel digital gains
};

// One 8-bit HWC frame: pixel (y, x) collects S = exposure_scale * sum_k
// row_drive[y][k] * images[k] (DN at the nominal exposure), gets Gaussian noise
// of variance S / electrons_per_dn + read^2 (Poisson shot noise of that many
// electrons in the normal approximation, which holds from a few electrons on),
// is multiplied by analog_gain * white_balance[c], rounded and clipped to 0..255.
void expose(const LedImages& images, const std::vector<std::array<double, 3>>& row_drive, int width,
            const Readout& readout, const CameraNoise& noise, NoiseStream& rng, std::uint8_t* out);

}  // namespace vkfuse::sim

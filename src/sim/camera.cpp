// Noise, gain, quantisation and saturation of the simulated camera (sim/camera.hpp).
#include "sim/camera.hpp"

#include <algorithm>
#include <cmath>

namespace vkfuse::sim {

void expose(const LedImages& images, const std::vector<std::array<double, 3>>& row_drive, int width,
            const Readout& readout, const CameraNoise& noise, NoiseStream& rng, std::uint8_t* out) {
    const double inv_electrons = 1.0 / noise.electrons_per_dn;
    const double read2 = noise.read_noise_dn * noise.read_noise_dn;
    const std::size_t row_values = std::size_t(width) * 3;
    std::array<double, 3> gain{};
    for (int c = 0; c < 3; ++c) gain[std::size_t(c)] = readout.analog_gain * readout.white_balance[std::size_t(c)];
    for (std::size_t y = 0; y < row_drive.size(); ++y) {
        std::array<double, 3> drive = row_drive[y];
        for (double& d : drive) d *= readout.exposure_scale;
        const float* r = &images[0][y * row_values];
        const float* g = &images[1][y * row_values];
        const float* b = &images[2][y * row_values];
        std::uint8_t* dst = out + y * row_values;
        for (std::size_t i = 0; i < row_values; ++i) {
            const double signal = drive[0] * r[i] + drive[1] * g[i] + drive[2] * b[i];
            const double value = gain[i % 3] * (signal + std::sqrt(signal * inv_electrons + read2) * rng.normal());
            // The ADC clips: a saturated pixel reads 255 whatever the light.
            dst[i] = std::uint8_t(std::clamp(std::nearbyint(value), 0.0, 255.0));
        }
    }
}

}  // namespace vkfuse::sim

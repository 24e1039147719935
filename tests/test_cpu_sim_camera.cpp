// The simulated camera's exposure: every instruction set expose() is built
// for writes the bytes of the plain per-sample formula, and the noise stream
// read ahead gives the values read one at a time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/camera.hpp"

namespace vkfuse::sim {
namespace {

TEST(SimCamera, NoiseReadAheadIsTheStreamReadInOrder) {
    NoiseStream ahead(7, 3), in_order(7, 3);
    for (std::uint64_t i = 0; i < 20; ++i) EXPECT_EQ(ahead.normal_ahead(i), in_order.normal()) << "draw " << i;
    ahead.skip(20);
    EXPECT_EQ(ahead.next(), in_order.next());
}

// The formula of sim/camera.hpp, one sample at a time in sample order, the
// draws taken with normal(): written without the loop structure expose()
// uses to vectorize.
std::vector<std::uint8_t> expose_one_by_one(const LedImages& images, const std::vector<std::array<double, 3>>& drive,
                                            int width, const Readout& readout, const CameraNoise& noise,
                                            NoiseStream& rng) {
    std::vector<std::uint8_t> out;
    for (std::size_t y = 0; y < drive.size(); ++y)
        for (int x = 0; x < width; ++x)
            for (std::size_t c = 0; c < 3; ++c) {
                const std::size_t i = (y * std::size_t(width) + std::size_t(x)) * 3 + c;
                double signal = 0;
                for (std::size_t k = 0; k < 3; ++k) signal += drive[y][k] * readout.exposure_scale * images[k][i];
                // Times the reciprocal, as expose() does: a division rounds differently.
                const double sigma =
                    std::sqrt(signal * (1.0 / noise.electrons_per_dn) + noise.read_noise_dn * noise.read_noise_dn);
                const double value = readout.analog_gain * readout.white_balance[c] * (signal + sigma * rng.normal());
                out.push_back(std::uint8_t(std::clamp(value, 0.0, 255.0) + 0.5));
            }
    return out;
}

TEST(SimCamera, EveryInstructionSetWritesTheBytesOfThePlainFormula) {
    // 37 pixels a row: 111 samples, so every vector width leaves a tail.
    const int width = 37, rows = 6;
    const std::size_t samples = std::size_t(width) * rows * 3;
    LedImages images;
    NoiseStream fill(99, 0);
    for (auto& plane : images) {
        plane.resize(samples);
        // Dark through saturated: 0..120 DN per LED at full drive.
        for (float& v : plane) v = float(std::abs(fill.normal()) * 40.0);
    }
    std::vector<std::array<double, 3>> drive;
    for (int y = 0; y < rows; ++y) drive.push_back({0.2 + 0.3 * y, 1.0 - 0.1 * y, 0.5});
    Readout readout;
    readout.exposure_scale = 1.3;
    readout.analog_gain = 1.7;
    readout.white_balance = {1.1, 0.9, 1.25};
    const CameraNoise noise = CameraNoise::digit();

    NoiseStream reference_rng(5, 11);
    const std::vector<std::uint8_t> expected = expose_one_by_one(images, drive, width, readout, noise, reference_rng);
    ASSERT_TRUE(std::any_of(expected.begin(), expected.end(), [](std::uint8_t v) { return v == 255; }));
    ASSERT_TRUE(std::any_of(expected.begin(), expected.end(), [](std::uint8_t v) { return v > 0 && v < 255; }));

    int ran = 0;
    for (ExposeIsa isa : {ExposeIsa::baseline, ExposeIsa::avx2, ExposeIsa::avx512}) {
        if (!expose_isa_supported(isa)) continue;
        ++ran;
        NoiseStream rng(5, 11);
        std::vector<std::uint8_t> got(samples);
        expose(isa, images, drive, width, readout, noise, rng, got.data());
        EXPECT_EQ(got, expected) << "instruction set " << int(isa);
        NoiseStream after = reference_rng;
        EXPECT_EQ(rng.next(), after.next()) << "instruction set " << int(isa) << " left the stream elsewhere";
    }
    EXPECT_GE(ran, 1);
    // The default picks one of them, so it writes the same bytes.
    NoiseStream rng(5, 11);
    std::vector<std::uint8_t> got(samples);
    expose(images, drive, width, readout, noise, rng, got.data());
    EXPECT_EQ(got, expected);
}

}  // namespace
}  // namespace vkfuse::sim

// sim_support.hpp - helpers the simulated-DIGIT tests share: frames as
// images, waiting for a setting to settle, simple statistics.
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "vkfuse/core/image.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::test {

// An 8-bit frame as docs/spec.md maps it: v / 255.
inline ImageD to_image(const Frame& f) {
    ImageD img(f.height, f.width, 3);
    for (std::size_t i = 0; i < f.pixels.size(); ++i) img.data[i] = f.pixels[i] / 255.0;
    return img;
}

// Per-channel means in DN (0..255).
inline std::array<double, 3> channel_means(const ImageD& img) {
    std::array<double, 3> m{};
    for (std::size_t i = 0; i < img.data.size(); ++i) m[i % 3] += img.data[i];
    for (double& v : m) v *= 255.0 / double(img.pixels());
    return m;
}

// Whether two frames were read out alike (the ISP has stopped moving).
inline bool same_readout(const SimFrameTruth& a, const SimFrameTruth& b, double tolerance = 1e-3) {
    double change = std::abs(a.exposure_s / b.exposure_s - 1) + std::abs(a.analog_gain / b.analog_gain - 1);
    for (std::size_t c = 0; c < 3; ++c) change += std::abs(a.white_balance[c] / b.white_balance[c] - 1);
    return change < tolerance;
}

// Requests setting and grabs until a frame is lit by it alone and the
// camera's auto exposure / white balance have settled; returns that frame.
// frames_taken (if given) receives how many frames that took.
inline Frame settle(SimDigit& sim, const Illumination& setting, int* frames_taken = nullptr) {
    sim.set_illumination(setting);
    SimFrameTruth previous;
    for (int n = 1; n <= 200; ++n) {
        Frame frame = sim.grab();
        const SimFrameTruth truth = sim.truth(frame.index);
        const bool lit = !truth.mixed && truth.lit_by == setting;
        if (lit && n > 1 && same_readout(truth, previous)) {
            if (frames_taken) *frames_taken = n;
            return frame;
        }
        previous = truth;
    }
    throw std::runtime_error("settle: the simulated DIGIT never settled on " + setting.to_string());
}

// Mean over 8x8 blocks of one channel (DN), row-major blocks: the
// low-frequency structure of a frame, noise averaged out.
inline std::vector<double> block_means(const ImageD& img, int channel, int block = 8) {
    std::vector<double> out;
    for (int by = 0; by + block <= img.height; by += block)
        for (int bx = 0; bx + block <= img.width; bx += block) {
            double sum = 0;
            for (int y = by; y < by + block; ++y)
                for (int x = bx; x < bx + block; ++x) sum += img.at(y, x, channel);
            out.push_back(255.0 * sum / (block * block));
        }
    return out;
}

inline double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    double ma = 0, mb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ma += a[i] / double(a.size());
        mb += b[i] / double(b.size());
    }
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ab += (a[i] - ma) * (b[i] - mb);
        aa += (a[i] - ma) * (a[i] - ma);
        bb += (b[i] - mb) * (b[i] - mb);
    }
    return ab / std::sqrt(aa * bb);
}

}  // namespace vkfuse::test

// sim/camera.hpp - the DIGIT's camera: a rolling shutter exposing rows while
// the LEDs switch, and the sensor's noise.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sim/lighting.hpp"
#include "vkfuse/sensor/illumination.hpp"

namespace vkfuse::sim {

// The simulator's noise source: a counter-based stream per (seed, frame), so
// a frame's noise depends on nothing but those two and frames can be rendered
// in any order with identical results.

class NoiseStream {
public:
    NoiseStream(std::uint64_t seed, std::uint64_t frame) : state_(mix(seed ^ mix(frame + 0x632BE59BD9B4E019ull))) {}

    // splitmix64: passes BigCrush, one add and three multiply-xorshifts.
    std::uint64_t next() { return mix(state_ += kGamma); }

    // Standard normal, approximated by the sum of four uniform 16-bit
    // draws from one 64-bit word (Irwin-Hall, variance matched): smooth,
    // tails to +-3.5 sigma, ten times cheaper than Box-Muller, which matters
    // at 230 000 samples per frame.
    double normal() { return to_normal(next()); }

    // The value the (i + 1)-th call of normal() from here would return,
    // and skipping n calls. The i-th draw is mix(state + (i + 1) * gamma),
    // so no draw waits for the one before it: a loop over a row's samples
    // takes its draws with normal_ahead(j), then skip(row), and vectorizes
    // where the target has 64-bit vector multiplies.
    double normal_ahead(std::uint64_t i) const { return to_normal(mix(state_ + (i + 1) * kGamma)); }
    void skip(std::uint64_t n) { state_ += n * kGamma; }

private:
    static constexpr std::uint64_t kGamma = 0x9E3779B97F4A7C15ull;

    static double to_normal(std::uint64_t r) {
        // The four draws added as integers (at most 18 bits): the double sum
        // of the same exact values, with one conversion instead of four.
        const double sum = double((r & 0xFFFF) + ((r >> 16) & 0xFFFF) + ((r >> 32) & 0xFFFF) + (r >> 48));
        constexpr double kMean = 4 * 32767.5;
        constexpr double kInvStd = 1.0 / 37837.23;  // sqrt(4 * (65536^2 - 1) / 12)
        return (sum - kMean) * kInvStd;
    }
    static std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    std::uint64_t state_;
};

// The image sensor: integrates each row's light, adds shot and read noise,
// amplifies, quantises to 8 bits and clips.

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

// The instruction sets expose() is built for; it runs the widest this CPU
// has. Every one writes the same bytes (the same IEEE operations in the same
// order, none contracted into an FMA); a test runs each the CPU supports.
enum class ExposeIsa { baseline, avx2, avx512 };
bool expose_isa_supported(ExposeIsa isa);
void expose(ExposeIsa isa, const LedImages& images, const std::vector<std::array<double, 3>>& row_drive, int width,
            const Readout& readout, const CameraNoise& noise, NoiseStream& rng, std::uint8_t* out);

// When light reaches which row: the LED switching timeline and the rolling
// shutter that samples it.

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

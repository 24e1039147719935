// The camera's exposure and rolling shutter (sim/camera.hpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/camera.hpp"
#include "sim/lighting.hpp"

namespace vkfuse::sim {

namespace {

// One call's arguments, handed to whichever build runs it.
struct Exposure {
    const LedImages& images;
    const std::vector<std::array<double, 3>>& row_drive;
    int width;
    const Readout& readout;
    const CameraNoise& noise;
    NoiseStream& rng;
    std::uint8_t* out;
};

// The body of every build of expose(), inlined into each. Sample j's noise
// draw is the stream's normal_ahead(j), which depends on no other sample, so
// the loop over a row's samples carries nothing from one to the next and the
// compiler takes it several samples at a time (the same operations in the
// same order on each, so the same bits). With AVX-512DQ the draws vectorize
// too (eight 64-bit multiplies an instruction) and are taken inside that
// loop. SSE2 and AVX2 have no 64-bit vector multiply, and the compiler's
// emulation of one is no faster than the scalar multiply, so there the row's
// draws come first, one at a time, into a buffer the vector loop reads
// (kDrawsInline false).
template <bool kDrawsInline>
[[gnu::always_inline]] inline void expose_rows(const Exposure& e) {
    const auto& [images, row_drive, width, readout, noise, rng, out] = e;
    const double inv_electrons = 1.0 / noise.electrons_per_dn;
    const double read2 = noise.read_noise_dn * noise.read_noise_dn;
    const std::size_t row_values = std::size_t(width) * 3;
    // A row's gains sample by sample (channel c of a pixel at 3x + c).
    std::vector<double> gains(row_values), normals(kDrawsInline ? 0 : row_values);
    for (std::size_t j = 0; j < row_values; ++j)
        gains[j] = readout.analog_gain * readout.white_balance[j % 3];
    // A local copy: stores through the 8-bit output may alias anything, so
    // the caller's stream would be reloaded and stored around every sample.
    NoiseStream local = rng;
    for (std::size_t y = 0; y < row_drive.size(); ++y) {
        std::array<double, 3> drive = row_drive[y];
        for (double& d : drive) d *= readout.exposure_scale;
        const float* r = &images[0][y * row_values];
        const float* g = &images[1][y * row_values];
        const float* b = &images[2][y * row_values];
        std::uint8_t* dst = out + y * row_values;
        if constexpr (!kDrawsInline)
            for (double& n : normals) n = local.normal();
        // Rounded inline: a libm call per sample was a third of a frame's
        // cost (x86-64's baseline has no rounding instruction). Halves round
        // up, where nearbyint would round to even: a tie needs noise exact to
        // 2^-40.
        for (std::size_t j = 0; j < row_values; ++j) {
            const double signal = drive[0] * r[j] + drive[1] * g[j] + drive[2] * b[j];
            double draw;
            if constexpr (kDrawsInline)
                draw = local.normal_ahead(j);
            else
                draw = normals[j];
            const double value = gains[j] * (signal + std::sqrt(signal * inv_electrons + read2) * draw);
            // The ADC clips: a saturated pixel reads 255 whatever the light.
            dst[j] = std::uint8_t(std::min(std::max(value, 0.0), 255.0) + 0.5);
        }
        if constexpr (kDrawsInline) local.skip(row_values);
    }
    rng = local;
}

void expose_baseline(const Exposure& e) { expose_rows<false>(e); }

#if defined(__x86_64__) && defined(__GNUC__)
#define VKFUSE_EXPOSE_X86 1
// Instruction sets, not arch=: GCC inlines a body into a function whose
// instruction sets contain its own, but not across a change of arch.
[[gnu::target("avx2")]] void expose_avx2(const Exposure& e) { expose_rows<false>(e); }
[[gnu::target("avx2,avx512f,avx512dq,avx512vl,avx512bw")]] void expose_avx512(const Exposure& e) {
    expose_rows<true>(e);
}
#endif

// The build for isa, which the CPU supports.
void expose_with(ExposeIsa isa, const Exposure& e) {
#ifdef VKFUSE_EXPOSE_X86
    if (isa == ExposeIsa::avx512) return expose_avx512(e);
    if (isa == ExposeIsa::avx2) return expose_avx2(e);
#endif
    expose_baseline(e);
}

ExposeIsa widest_supported() {
    for (ExposeIsa isa : {ExposeIsa::avx512, ExposeIsa::avx2})
        if (expose_isa_supported(isa)) return isa;
    return ExposeIsa::baseline;
}

}  // namespace

bool expose_isa_supported(ExposeIsa isa) {
    switch (isa) {
    case ExposeIsa::baseline: return true;
#ifdef VKFUSE_EXPOSE_X86
    case ExposeIsa::avx2: return __builtin_cpu_supports("avx2");
    case ExposeIsa::avx512:
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw");
#else
    case ExposeIsa::avx2:
    case ExposeIsa::avx512: return false;
#endif
    }
    return false;
}

void expose(ExposeIsa isa, const LedImages& images, const std::vector<std::array<double, 3>>& row_drive, int width,
            const Readout& readout, const CameraNoise& noise, NoiseStream& rng, std::uint8_t* out) {
    if (!expose_isa_supported(isa))
        throw std::invalid_argument("sim::expose: this CPU lacks the instruction set asked for");
    expose_with(isa, {images, row_drive, width, readout, noise, rng, out});
}

void expose(const LedImages& images, const std::vector<std::array<double, 3>>& row_drive, int width,
            const Readout& readout, const CameraNoise& noise, NoiseStream& rng, std::uint8_t* out) {
    expose_with(widest_supported(), {images, row_drive, width, readout, noise, rng, out});
}

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

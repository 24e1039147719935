// stress_support.hpp - what the stress tests share: frames made of float32
// values (so that both backends start from the same numbers), one GPU cycle,
// error measures that also work on images far outside [0, 1], and a line per
// case with its worst error so a run documents how close each case came.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::test {

// float32 images in [0, 1] from test_support, as Image.
Image random_frame(int height, int width, int channels, std::uint32_t seed);
Image structured_frame(int height, int width, int channels, std::uint32_t seed);

std::vector<ImageD> to_double(const std::vector<Image>& frames);
// Every sample multiplied by a in float32 (what a caller scaling its frames gets).
Image scaled(const Image& image, float a);

// One cycle on the GPU: frames sensor-major (S * K of them), fused images and
// metrics (when want_metrics) of every sensor.
struct GpuCycle {
    std::vector<Image> fused;
    std::vector<Metrics> metrics;
};
GpuCycle gpu_cycle(Context& ctx, const FusionSpec& spec, const std::vector<Image>& frames, int frames_per_sensor,
                   bool want_metrics = true);
// Metrics of one image on the GPU (an unfused plan: PlanConfig::fuse false).
Metrics gpu_metrics(Context& ctx, const Image& image, const Image* background = nullptr);

// Index of the first NaN or Inf, or -1 when every sample is finite.
long first_non_finite(const Image& image);
long first_non_finite(const ImageD& image);
bool finite(const Metrics& m);
double max_abs(const ImageD& image);

// |got - ref| / |ref|; 0 when both are 0 and infinity when only ref is 0, so
// an exact zero (the contrast of a constant image) must come out exactly zero.
double relative_error(double got, double ref);

// Samples of gpu farther than tolerance from ref, and the largest distance.
struct Mismatch {
    std::size_t over = 0;
    double worst = 0;
};
Mismatch compare(const Image& gpu, const ImageD& ref, double tolerance);

// The spec's defaults with the given method, or wavelet/mode/levels.
FusionSpec method_spec(Method method, int levels = 0);
FusionSpec wavelet_spec(Wavelet wavelet, WaveletMode mode, int levels);
std::string describe(const FusionSpec& spec);
// Brovey, channel-sum, Laplacian (default levels) and every wavelet in both
// modes at 3 levels, each with docs/spec.md's default rules (max-abs details).
std::vector<FusionSpec> every_method();
// Base mean, detail max: max-abs may pick a different frame than double where
// two coefficients are equal in magnitude and opposite in sign up to rounding
// (README "Accuracy"); max has no such flip (near-equal values are near-equal
// results), so comparisons that must hold at every sample use these rules.
FusionSpec tie_free(FusionSpec spec);
// Levels that take a Laplacian pyramid of height x width down to 1 x 1.
int levels_to_one_pixel(int height, int width);

inline constexpr Wavelet kAllWavelets[] = {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44};
inline constexpr WaveletMode kAllModes[] = {WaveletMode::Periodization, WaveletMode::Symmetric};

// Prints "[ worst    ] <what>: <value>" so the test log records the margins.
void report(const std::string& what, double value);

}  // namespace vkfuse::test

// Box-filter Gaussian approximation for the simulator's rasters.
#include "sim/raster.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace vkfuse::sim {
namespace {

// Box of half-width r along one line of n samples spaced by stride, in place
// via a scratch copy; samples past either end repeat the end value.
void box_line(float* line, int n, std::ptrdiff_t stride, int r, std::vector<float>& scratch) {
    scratch.resize(std::size_t(n));
    for (int i = 0; i < n; ++i) scratch[std::size_t(i)] = line[i * stride];
    auto sample = [&](int i) { return double(scratch[std::size_t(std::clamp(i, 0, n - 1))]); };
    double sum = 0;
    for (int i = -r; i <= r; ++i) sum += sample(i);
    const double norm = 1.0 / (2 * r + 1);
    for (int i = 0; i < n; ++i) {
        line[i * stride] = float(sum * norm);
        sum += sample(i + r + 1) - sample(i - r);
    }
}

void box_pass(Raster& img, int r) {
    std::vector<float> scratch;
    for (int y = 0; y < img.height; ++y) box_line(&img.at(y, 0), img.width, 1, r, scratch);
    for (int x = 0; x < img.width; ++x) box_line(&img.at(0, x), img.height, img.width, r, scratch);
}

// Below this sigma the box widths are too coarse to hit sigma; a sampled
// kernel is exact there and still cheap.
constexpr double kBoxFromSigma = 3.0;

// Sampled, normalised Gaussian along one line (clamped ends).
void kernel_line(float* line, int n, std::ptrdiff_t stride, const std::vector<double>& k,
                 std::vector<float>& scratch) {
    const int r = int(k.size()) / 2;
    scratch.resize(std::size_t(n));
    for (int i = 0; i < n; ++i) scratch[std::size_t(i)] = line[i * stride];
    for (int i = 0; i < n; ++i) {
        double sum = 0;
        for (int j = -r; j <= r; ++j) sum += k[std::size_t(j + r)] * scratch[std::size_t(std::clamp(i + j, 0, n - 1))];
        line[i * stride] = float(sum);
    }
}

void kernel_pass(Raster& img, double sigma) {
    const int r = int(std::ceil(3 * sigma));
    std::vector<double> k(std::size_t(2 * r + 1));
    double total = 0;
    for (int j = -r; j <= r; ++j) total += k[std::size_t(j + r)] = std::exp(-0.5 * j * j / (sigma * sigma));
    for (double& w : k) w /= total;
    std::vector<float> scratch;
    for (int y = 0; y < img.height; ++y) kernel_line(&img.at(y, 0), img.width, 1, k, scratch);
    for (int x = 0; x < img.width; ++x) kernel_line(&img.at(0, x), img.height, img.width, k, scratch);
}

// Running maximum of half-width r along one line, with a monotonic deque of
// indices (each sample enters and leaves once: linear in n whatever r).
void max_line(float* line, int n, std::ptrdiff_t stride, int r, std::vector<float>& scratch, std::deque<int>& window) {
    scratch.resize(std::size_t(n));
    for (int i = 0; i < n; ++i) scratch[std::size_t(i)] = line[i * stride];
    window.clear();
    int next = 0;
    for (int i = 0; i < n; ++i) {
        for (; next < n && next <= i + r; ++next) {
            while (!window.empty() && scratch[std::size_t(window.back())] <= scratch[std::size_t(next)]) window.pop_back();
            window.push_back(next);
        }
        while (window.front() < i - r) window.pop_front();
        line[i * stride] = scratch[std::size_t(window.front())];
    }
}

}  // namespace

void max_filter(Raster& img, int radius) {
    std::vector<float> scratch;
    std::deque<int> window;
    for (int y = 0; y < img.height; ++y) max_line(&img.at(y, 0), img.width, 1, radius, scratch, window);
    for (int x = 0; x < img.width; ++x) max_line(&img.at(0, x), img.height, img.width, radius, scratch, window);
}

void gaussian_blur(Raster& r, double sigma_px) {
    if (sigma_px <= 0) return;
    if (sigma_px < kBoxFromSigma) return kernel_pass(r, sigma_px);
    // Three boxes of width w have variance 3 (w^2 - 1) / 12 = sigma^2.
    const int half = int(std::lround((std::sqrt(4.0 * sigma_px * sigma_px + 1.0) - 1.0) / 2.0));
    for (int pass = 0; pass < 3; ++pass) box_pass(r, half);
}

}  // namespace vkfuse::sim

#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace vkfuse::test {

ImageD random_image(int height, int width, int channels, std::uint32_t seed) {
    ImageD img(height, width, channels);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(0.0f, 1.0f);
    for (auto& v : img.data) v = double(dist(rng));
    return img;
}

ImageD structured_image(int height, int width, int channels, std::uint32_t seed) {
    ImageD img(height, width, channels);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> noise(-0.02f, 0.02f);
    const double cx = width * (0.3 + 0.4 * (seed % 7) / 7.0), cy = height * 0.5;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c) {
                double r = std::hypot(x - cx, y - cy);
                double v = 0.4 + 0.2 * std::sin(0.35 * x + c) * std::cos(0.21 * y)
                         + (r < std::min(width, height) * 0.25 ? 0.25 : 0.0) + 0.1 * (c + 1) * y / std::max(1, height);
                img.at(y, x, c) = double(float(std::clamp(v + noise(rng), 0.0, 1.0)));
            }
    return img;
}

double max_abs_diff(const ImageD& a, const ImageD& b) {
    if (!a.same_shape(b)) throw std::invalid_argument("max_abs_diff: shapes differ");
    double m = 0;
    for (std::size_t i = 0; i < a.data.size(); ++i) m = std::max(m, std::abs(a.data[i] - b.data[i]));
    return m;
}

double max_abs_diff(const Image& a, const ImageD& b) { return max_abs_diff(convert<double>(a), b); }

std::string data_path(const std::string& name) { return std::string(VKFUSE_TEST_DATA) + "/" + name; }

std::vector<FusionSpec> every_pyramid_and_wavelet_max_abs() {
    std::vector<FusionSpec> specs;
    FusionSpec lap;
    lap.method = Method::Laplacian;
    specs.push_back(lap);
    for (Wavelet w : {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44})
        for (WaveletMode m : {WaveletMode::Periodization, WaveletMode::Symmetric}) {
            FusionSpec s;
            s.method = Method::Wavelet;
            s.wavelet = w;
            s.mode = m;
            specs.push_back(s);
        }
    for (FusionSpec& s : specs) s.base_rule = s.detail_rule = Rule::MaxAbs;
    return specs;
}

}  // namespace vkfuse::test

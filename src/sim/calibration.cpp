// Least-squares LED light fields from a real frame (sim/calibration.hpp).
#include "sim/calibration.hpp"

#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "sim/raster.hpp"

namespace vkfuse::sim {
namespace {

constexpr int kBlock = 8;
constexpr int kTerms = std::tuple_size_v<LightField>;
constexpr int kUnknowns = 3 * kTerms;

// Solves the (symmetric positive definite) normal equations by Gaussian
// elimination with partial pivoting; 30 unknowns, so nothing fancier is needed.
std::vector<double> solve(std::vector<std::vector<double>> a, std::vector<double> b) {
    const std::size_t n = b.size();
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t pivot = i;
        for (std::size_t j = i + 1; j < n; ++j)
            if (std::abs(a[j][i]) > std::abs(a[pivot][i])) pivot = j;
        std::swap(a[i], a[pivot]);
        std::swap(b[i], b[pivot]);
        for (std::size_t j = i + 1; j < n; ++j) {
            const double f = a[j][i] / a[i][i];
            for (std::size_t k = i; k < n; ++k) a[j][k] -= f * a[i][k];
            b[j] -= f * b[i];
        }
    }
    std::vector<double> x(n);
    for (std::size_t i = n; i-- > 0;) {
        double s = b[i];
        for (std::size_t k = i + 1; k < n; ++k) s -= a[i][k] * x[k];
        x[i] = s / a[i][i];
    }
    return x;
}

// Mean of one 8x8 block of channel c, in DN.
double block_mean(const ImageD& frame, int by, int bx, int c) {
    double sum = 0;
    for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
        for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) sum += frame.at(y, x, c);
    return 255.0 * sum / (kBlock * kBlock);
}

}  // namespace

std::array<LightField, 3> fit_light_fields(const ImageD& frame, const Crosstalk& crosstalk) {
    const Grid grid = Grid::qvga();
    if (frame.width != grid.width || frame.height != grid.height || frame.channels != 3)
        throw std::invalid_argument("fit_light_fields: needs a landscape 320x240 RGB frame");
    const Grid blocks{grid.width / kBlock, grid.height / kBlock, grid.mm_per_px * kBlock};
    std::vector<std::vector<double>> normal(kUnknowns, std::vector<double>(kUnknowns, 0.0));
    std::vector<double> rhs(kUnknowns, 0.0);
    std::array<double, kUnknowns> row{};
    for (int by = 0; by < blocks.height; ++by)
        for (int bx = 0; bx < blocks.width; ++bx) {
            const LightField t = light_field_terms(blocks.x_mm(bx), blocks.y_mm(by));
            for (int c = 0; c < 3; ++c) {
                // One observation: channel c of this block, linear in all 30 coefficients.
                for (int k = 0; k < 3; ++k)
                    for (int j = 0; j < kTerms; ++j)
                        row[std::size_t(k * kTerms + j)] = crosstalk[std::size_t(c)][std::size_t(k)] * t[std::size_t(j)];
                const double value = block_mean(frame, by, bx, c);
                for (int i = 0; i < kUnknowns; ++i) {
                    rhs[std::size_t(i)] += row[std::size_t(i)] * value;
                    for (int j = 0; j < kUnknowns; ++j) normal[std::size_t(i)][std::size_t(j)] += row[std::size_t(i)] * row[std::size_t(j)];
                }
            }
        }
    const std::vector<double> x = solve(normal, rhs);
    std::array<LightField, 3> fields{};
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < kTerms; ++j) fields[std::size_t(k)][std::size_t(j)] = x[std::size_t(k * kTerms + j)];
    return fields;
}

ImageD landscape_from_portrait(const ImageD& portrait) {
    ImageD out(portrait.width, portrait.height, portrait.channels);
    for (int r = 0; r < out.height; ++r)
        for (int c = 0; c < out.width; ++c)
            for (int ch = 0; ch < out.channels; ++ch) out.at(r, c, ch) = portrait.at(portrait.height - 1 - c, r, ch);
    return out;
}

}  // namespace vkfuse::sim

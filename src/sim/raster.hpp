// sim/raster.hpp - the simulator's unit of work: one float value per
// pixel of the camera grid, and the camera grid itself in millimetres.
#pragma once
#include <cstddef>
#include <vector>

namespace vkfuse::sim {

// The gel as the camera sees it: a fixed field of view sampled at the stream's
// resolution, landscape as the DIGIT's sensor reads it out (320x240 / 640x480).
struct Grid {
    static constexpr double kFieldWidthMm = 20.0;   // DIGIT sensing area, about 20 x 15 mm
    static constexpr double kFieldHeightMm = 15.0;

    int width = 0;
    int height = 0;
    double mm_per_px = 0;

    static Grid qvga() { return {320, 240, kFieldWidthMm / 320}; }
    static Grid vga() { return {640, 480, kFieldWidthMm / 640}; }

    std::size_t size() const { return std::size_t(width) * std::size_t(height); }
    // Pixel centres in millimetres from the centre of the field, y growing downwards.
    double x_mm(int col) const { return (col + 0.5 - 0.5 * width) * mm_per_px; }
    double y_mm(int row) const { return (row + 0.5 - 0.5 * height) * mm_per_px; }
};

struct Raster {
    int width = 0;
    int height = 0;
    std::vector<float> v;  // row-major

    Raster() = default;
    Raster(int w, int h, float fill = 0) : width(w), height(h), v(std::size_t(w) * std::size_t(h), fill) {}
    explicit Raster(const Grid& g, float fill = 0) : Raster(g.width, g.height, fill) {}

    float& at(int y, int x) { return v[std::size_t(y) * width + x]; }
    float at(int y, int x) const { return v[std::size_t(y) * width + x]; }
};

// Gaussian blur of standard deviation sigma_px, as three box passes per axis
// (within a few percent of a true Gaussian, cost independent of sigma); edges
// are clamped, like a gel that continues past the field of view.
void gaussian_blur(Raster& r, double sigma_px);

// Maximum over the (2 radius + 1)^2 square around each pixel (clipped at the edges).
void max_filter(Raster& r, int radius);

}  // namespace vkfuse::sim

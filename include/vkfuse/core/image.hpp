// vkfuse/core/image.hpp - owned images and borrowed frame views.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vkfuse {

// An owned H x W x C image, channels interleaved (row-major HWC, like a .npy
// of shape (H, W, C)). C is 1 (gray) or 3 (RGB). Values are nominally in [0, 1]
// but never clamped: fused results may leave that range.
template <class T>
struct BasicImage {
    int height = 0;
    int width = 0;
    int channels = 0;
    std::vector<T> data;

    BasicImage() = default;
    BasicImage(int h, int w, int c) : height(h), width(w), channels(c), data(std::size_t(h) * w * c) {}

    std::size_t pixels() const { return std::size_t(height) * width; }
    std::size_t size() const { return data.size(); }
    T& at(int y, int x, int c) { return data[(std::size_t(y) * width + x) * channels + c]; }
    const T& at(int y, int x, int c) const { return data[(std::size_t(y) * width + x) * channels + c]; }
    bool same_shape(const BasicImage& o) const {
        return height == o.height && width == o.width && channels == o.channels;
    }
};

using Image = BasicImage<float>;    // what the GPU path and files exchange
using ImageD = BasicImage<double>;  // what the CPU reference path computes in

template <class To, class From>
BasicImage<To> convert(const BasicImage<From>& in) {
    BasicImage<To> out;
    out.height = in.height;
    out.width = in.width;
    out.channels = in.channels;
    out.data.assign(in.data.begin(), in.data.end());
    return out;
}

// How the pixels of a borrowed frame are stored.
enum class PixelType {
    U8,   // 0..255, mapped to v / 255 (what a camera delivers)
    F32,  // float, used as is
};

// A borrowed, tightly packed HWC frame (a camera buffer, an Image's data).
struct FrameView {
    const void* data = nullptr;
    int height = 0;
    int width = 0;
    int channels = 0;
    PixelType type = PixelType::F32;

    static FrameView of(const Image& img) {
        return {img.data.data(), img.height, img.width, img.channels, PixelType::F32};
    }
    std::size_t bytes() const {
        return std::size_t(height) * width * channels * (type == PixelType::U8 ? 1 : 4);
    }
};

}  // namespace vkfuse

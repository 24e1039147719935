// Change detection on the CPU: the reference the device's change_detect
// kernel is tested against, and what the CPU fusion path runs.
#include "vkfuse/core/skip.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "vkfuse/core/error.hpp"

namespace vkfuse {

std::string_view to_string(SkipPolicy policy) {
    switch (policy) {
        case SkipPolicy::Off: return "off";
        case SkipPolicy::Idle: return "idle";
        case SkipPolicy::Static: return "static";
        case SkipPolicy::Tiles: return "tiles";
    }
    return "?";
}

std::optional<SkipPolicy> parse_skip_policy(std::string_view text) {
    for (SkipPolicy p : {SkipPolicy::Off, SkipPolicy::Idle, SkipPolicy::Static, SkipPolicy::Tiles})
        if (text == to_string(p)) return p;
    return std::nullopt;
}

std::uint16_t skip_mean_fixed(float mean) {
    const double v = std::round(double(mean) * kMeanSteps);
    return std::uint16_t(std::clamp(v, 0.0, 65535.0));
}

int skip_tiles_x(int width) { return (width + kSkipTile - 1) / kSkipTile; }
int skip_tiles_y(int height) { return (height + kSkipTile - 1) / kSkipTile; }

Image background_deviation(std::span<const FrameView> frames, const Image& mean) {
    Image out(mean.height, mean.width, mean.channels);
    if (frames.size() < 2) return out;
    std::vector<double> m2(out.size(), 0.0);
    for (const FrameView& f : frames) {
        if (f.height != mean.height || f.width != mean.width || f.channels != mean.channels)
            throw Error(ErrorKind::Shape, "background deviation: a frame's shape differs from its mean's");
        for (std::size_t i = 0; i < m2.size(); ++i) {
            const double v = f.type == PixelType::U8 ? double(static_cast<const std::uint8_t*>(f.data)[i]) / 255.0
                                                     : double(static_cast<const float*>(f.data)[i]);
            const double d = v - double(mean.data[i]);
            m2[i] += d * d;
        }
    }
    for (std::size_t i = 0; i < m2.size(); ++i) out.data[i] = float(std::sqrt(m2[i] / double(frames.size() - 1)));
    return out;
}

void check_skip_reference(const SkipReference& r, int height, int width, int channels, int frames,
                          const std::string_view what) {
    const std::string name(what);
    if (r.mean.size() != std::size_t(frames) || r.deviation.size() != std::size_t(frames))
        throw Error(ErrorKind::InvalidArgument, name + ": " + std::to_string(r.mean.size()) + " means and " +
                                                    std::to_string(r.deviation.size()) + " deviations for " +
                                                    std::to_string(frames) + " frames per cycle");
    for (const std::vector<Image>* field : {&r.mean, &r.deviation})
        for (const Image& img : *field) {
            if (img.height != height || img.width != width || img.channels != channels ||
                img.data.size() != std::size_t(height) * std::size_t(width) * std::size_t(channels))
                throw Error(ErrorKind::Shape, name + ": an image of " + std::to_string(img.width) + "x" +
                                                  std::to_string(img.height) + "x" + std::to_string(img.channels) +
                                                  " where the frames are " + std::to_string(width) + "x" +
                                                  std::to_string(height) + "x" + std::to_string(channels));
            for (float v : img.data)
                if (!std::isfinite(v)) throw Error(ErrorKind::Numeric, name + ": holds NaN or Inf");
        }
}

// kMinTileNoise (half an 8-bit level) in steps, written so that it is exact:
// (0.5 / 255) x kMeanSteps in floating point need not be.
constexpr double kMinNoiseSteps = 0.5 * 256.0;

std::vector<float> tile_noise(const SkipReference& r) {
    const Image& first = r.deviation.at(0);
    const int tx = skip_tiles_x(first.width), ty = skip_tiles_y(first.height), C = first.channels;
    const std::size_t tiles = std::size_t(tx) * std::size_t(ty);
    std::vector<float> out(r.deviation.size() * tiles);
    for (std::size_t k = 0; k < r.deviation.size(); ++k) {
        const Image& dev = r.deviation[k];
        for (int t = 0; t < int(tiles); ++t) {
            const int x0 = (t % tx) * kSkipTile, y0 = (t / tx) * kSkipTile;
            const int x1 = std::min(x0 + kSkipTile, dev.width), y1 = std::min(y0 + kSkipTile, dev.height);
            double sum = 0;
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x)
                    for (int c = 0; c < C; ++c) sum += double(dev.at(y, x, c)) * double(dev.at(y, x, c));
            const double rms = std::sqrt(sum / double((x1 - x0) * (y1 - y0) * C));
            out[k * tiles + std::size_t(t)] = float(std::max(rms * kMeanSteps, kMinNoiseSteps));
        }
    }
    return out;
}

namespace {

// A sample in steps (kMeanSteps to the unit): an 8-bit level is 256 of them, exactly.
double sample(const FrameView& f, std::size_t i) {
    return f.type == PixelType::U8 ? double(static_cast<const std::uint8_t*>(f.data)[i]) * 256.0
                                   : double(static_cast<const float*>(f.data)[i]) * kMeanSteps;
}

// The largest distance(k, i) / noise of its tile and setting, per tile.
template <class Distance>
std::vector<double> tile_scores(const SkipReference& r, std::size_t frames, double noise_scale, Distance distance) {
    const Image& first = r.mean.at(0);
    const int H = first.height, W = first.width, C = first.channels;
    const int tx = skip_tiles_x(W);
    const std::size_t tiles = std::size_t(tx) * std::size_t(skip_tiles_y(H));
    const std::vector<float> noise = tile_noise(r);
    std::vector<double> scores(tiles, 0.0);
    for (std::size_t k = 0; k < frames; ++k)
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const std::size_t t = std::size_t(y / kSkipTile) * std::size_t(tx) + std::size_t(x / kSkipTile);
                for (int c = 0; c < C; ++c) {
                    const std::size_t i = (std::size_t(y) * W + x) * C + c;
                    scores[t] = std::max(scores[t], distance(k, i) / (double(noise[k * tiles + t]) * noise_scale));
                }
            }
    return scores;
}

}  // namespace

std::vector<double> change_scores_reference(std::span<const FrameView> frames, const SkipReference& r) {
    return tile_scores(r, frames.size(), 1.0, [&](std::size_t k, std::size_t i) {
        return std::abs(sample(frames[k], i) - double(skip_mean_fixed(r.mean.at(k).data[i])));
    });
}

std::vector<double> static_scores_reference(std::span<const FrameView> frames, std::span<const FrameView> previous,
                                            const SkipReference& r) {
    return tile_scores(r, frames.size(), std::sqrt(2.0), [&](std::size_t k, std::size_t i) {
        return std::abs(sample(frames[k], i) - sample(previous[k], i));
    });
}

}  // namespace vkfuse

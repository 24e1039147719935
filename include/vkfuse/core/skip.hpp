// vkfuse/core/skip.hpp - skipping what a scene does not need (docs/spec.md,
// "Skipping"): a cycle whose frames stay within the sensor's background noise
// is not fused; its result is the fused background.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "vkfuse/core/image.hpp"

namespace vkfuse {

enum class SkipPolicy {
    Off,     // every cycle of every sensor is fused
    Idle,    // a sensor none of whose tiles changed from its background is not fused (it is "idle")
    // Idle, and a sensor none of whose tiles changed since the last cycle it
    // was fused reuses that cycle's result (a held, still press).
    Static,
    // Static, and a changed sensor fuses only what its changed tiles need
    // (their rectangle, and the halo the method reaches through); the rest of
    // its result is its fused reference. Periodization wavelets in float32
    // planes; any other fusion fuses a changed sensor whole, as Static.
    Tiles,
};
// Whether the policy reuses a held press's last result (Static and Tiles).
inline bool reuses_still_presses(SkipPolicy p) { return p == SkipPolicy::Static || p == SkipPolicy::Tiles; }
std::string_view to_string(SkipPolicy policy);  // "off", "idle", "static", "tiles"
std::optional<SkipPolicy> parse_skip_policy(std::string_view text);

// Change detection works on square tiles of this many pixels a side (the
// last row and column of tiles may be cut short by the frame's edge).
inline constexpr int kSkipTile = 32;

// The noise of a tile never counts as less than half an 8-bit step: a
// background of identical frames (a noiseless camera) still lets a sample
// move by rounding without its tile counting as changed.
inline constexpr double kMinTileNoise = 0.5 / 255.0;

struct SkipConfig {
    SkipPolicy policy = SkipPolicy::Off;
    // k: a tile changed when one of its samples, in any frame of the cycle,
    // lies more than k times the tile's noise from its background mean.
    // The default keeps a still, untouched simulated DIGIT idle (docs/spec.md).
    double threshold = 8.0;
};

// The part of a frame a cycle fused: rows top .. top + height - 1 and
// columns left .. left + width - 1, each taken modulo the frame's size (the
// rectangle may wrap past an edge, as a periodic wavelet does). Its pixels
// are full fusion's; the others are the fused reference's.
struct SkipRegion {
    int top = 0, height = 0, left = 0, width = 0;
    bool contains(int y, int x, int frame_height, int frame_width) const {
        return (y - top + frame_height) % frame_height < height && (x - left + frame_width) % frame_width < width;
    }
    // Its share of the frame (SkipOutcome::fused_fraction).
    double share(int frame_height, int frame_width) const {
        return double(height) * double(width) / (double(frame_height) * double(frame_width));
    }
};

// How one sensor's cycle was treated (Plan::skip_outcome, SensorCycle::skip).
struct SkipOutcome {
    bool idle = false;             // not fused: its result is the fused reference and that image's metrics
    bool reused = false;           // not fused: its result is that of the last cycle it was fused in
    double fused_fraction = 1;     // share of the frame fused this run (fused_region's area)
    double changed_fraction = 1;   // share of tiles whose score exceeded the threshold
    double score = 0;              // the largest tile score
    SkipRegion fused_region;       // what was fused: empty when idle or reused, else the whole frame or (Tiles) part
};

// What a sensor's frames are compared with: for each frame k of a cycle (lit
// by setting k of the sequence), the per-pixel mean of background frames
// under that setting and their per-pixel standard deviation. Both are float32
// images of the frames' shape, values on the frames' [0, 1] scale.
struct SkipReference {
    std::vector<Image> mean;       // K images
    std::vector<Image> deviation;  // K images
};

// The per-pixel, per-channel sample standard deviation (n - 1) of frames
// about their mean; zero for a single frame.
Image background_deviation(std::span<const FrameView> frames, const Image& mean);

// Tiles across and down a frame of width x height.
int skip_tiles_x(int width);
int skip_tiles_y(int height);

// Means are compared at 1/256 of an 8-bit level: the device holds them as
// 16-bit fixed point, round(mean x 255 x 256) clamped to 0..65535.
inline constexpr double kMeanSteps = 255.0 * 256.0;
std::uint16_t skip_mean_fixed(float mean);

// Each tile's noise under each setting, in steps of 1/256 of an 8-bit level
// (the means' fixed point): the root mean square of the deviation over the
// tile's samples times kMeanSteps, at least kMinTileNoise's 128 steps. In
// those units a change over a noiseless background scores exactly (4 levels:
// 1024 / 128 = 8), so a score equal to the threshold is one. K x tiles
// values, setting-major (tile t of setting k at k * tiles + t), tiles row-major.
std::vector<float> tile_noise(const SkipReference& reference);


// The change score of every tile (row-major): the largest |frame_k - mean_k|
// over the tile's samples and the K frames (mean_k as skip_mean_fixed holds
// it), divided by the tile's noise under setting k, both in steps. In double
// precision: what the device's scores are tested against. Frames are U8
// (v x 256 steps) or F32 (v x kMeanSteps).
std::vector<double> change_scores_reference(std::span<const FrameView> frames, const SkipReference& reference);

// SkipPolicy::Static: each tile's largest |frame_k - previous_k| against the
// frames of the last fused cycle, in units of the noise of a difference of
// two frames (the tile's noise times sqrt 2).
std::vector<double> static_scores_reference(std::span<const FrameView> frames, std::span<const FrameView> previous,
                                            const SkipReference& reference);

// Throws Error(InvalidArgument) naming `what` unless reference holds K
// finite images of shape height x width x channels in both fields.
void check_skip_reference(const SkipReference& reference, int height, int width, int channels, int frames,
                          const std::string_view what);

}  // namespace vkfuse

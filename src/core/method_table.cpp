// The fusion methods' rows (core/method_table.hpp).
#include "core/method_table.hpp"

#include "core/fusion_methods.hpp"
#include "core/validate_shape.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::core {
namespace {

// A Laplacian pyramid halves each side (rounding up), so 31 levels take any
// image an int can size down to 1 x 1 and deeper ones only repeat that top;
// the bound keeps an absurd --levels from recording a level per unit.
constexpr int kMaxLaplacianLevels = 32;
// A wavelet level needs both sides >= 2 (F - 1) and halves them: 31 levels
// exceed what any int-sized image carries, so the size decides first.
constexpr int kMaxWaveletLevels = 31;

// Periodization wavelets are fused tile-sparsely: their coefficients over a
// rectangle depend on a window of the frames its filter lengths bound.
bool periodization_only(const FusionSpec& spec) { return spec.mode == WaveletMode::Periodization; }

// In enum order: method_table() hands these out as one span.
const MethodInfo kRows[] = {
    {Method::ChannelSum, "channel-sum", "R from frame 1, G from frame 2, B from frame 3 (K = 3, RGB)", "channel-sum",
     0, 0, 3, 3, "red, green, blue LED", false, true, fuse_channel_sum, 0, 0, "#1f77b4", nullptr},
    {Method::Brovey, "brovey", "each frame weighted by its share of the pixel's sum", "brovey", 0, 0, 0, 0, "",
     false, false, fuse_brovey, 0, 0, "#ff7f0e", nullptr},
    {Method::Laplacian, "laplacian", "OpenCV-exact Laplacian pyramids, fused level by level", "a Laplacian pyramid",
     4, kMaxLaplacianLevels, 0, 0, "31 reach 1x1 from any size", false, false, fuse_laplacian, 1.7, 2.0, "#2ca02c",
     nullptr},
    {Method::Wavelet, "wavelet", "PyWavelets' 2-D DWT, bands fused by the rules", "a wavelet transform", 3,
     kMaxWaveletLevels, 0, 0, "no image carries more", true, false, fuse_wavelet, 1.7, 2.0, "#e377c2",
     periodization_only},
};

}  // namespace

const MethodInfo& method_info(Method m) {
    // No default: a Method without its row here fails to compile (-Wswitch).
    switch (m) {
        case Method::ChannelSum: return kRows[0];
        case Method::Brovey: return kRows[1];
        case Method::Laplacian: return kRows[2];
        case Method::Wavelet: return kRows[3];
    }
    throw Error(ErrorKind::InvalidArgument, "--method: invalid method enumerator");
}

std::span<const MethodInfo> method_table() { return kRows; }

bool fuses_tile_sparse(const FusionSpec& spec) {
    const MethodInfo& row = method_info(spec.method);
    return row.tile_sparse && row.tile_sparse(spec);
}

std::string with_method_names(std::string_view help, std::string_view last_separator) {
    std::string out(help);
    const std::string_view key = "{methods}";
    if (const std::size_t at = out.find(key); at != std::string::npos)
        out.replace(at, key.size(), method_names(last_separator));
    return out;
}

std::string method_names(std::string_view last_separator) {
    std::string out;
    const auto rows = method_table();
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (i > 0) out += i + 1 == rows.size() ? last_separator : std::string_view(", ");
        out += rows[i].name;
    }
    return out;
}

}  // namespace vkfuse::core

namespace vkfuse {

// fuse_reference(): validation, then the method's row (include/vkfuse/core/reference.hpp).
ImageD fuse_reference(std::span<const ImageD> frames, const FusionSpec& spec) {
    if (frames.empty()) validate(spec, 1, 1, 1, 0);  // throws the frame-count message
    validate(spec, frames[0].height, frames[0].width, frames[0].channels, int(frames.size()));
    core::check_frames(frames);
    return core::method_info(spec.method).reference(frames, spec);
}

}  // namespace vkfuse

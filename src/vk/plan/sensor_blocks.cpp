// A plan's sensors in blocks whose buffers one descriptor binds whole
// (vk/plan/sensor_blocks.hpp).
#include "vk/plan/sensor_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "vk/plan/method_recorders.hpp"

namespace vkfuse::vk {

double plan_buffer_bytes(const PlanConfig& cfg, PlanKind kind) {
    const bool pointwise = kind == PlanKind::BackgroundMean ||
                           (kind == PlanKind::Fuse && method_recorder(cfg.fusion.method).shape == GraphShape::Pointwise);
    if (!pointwise && kind != PlanKind::Score) return largest_buffer_bytes(cfg);
    // The frames as uploaded, or one plane set (or HWC image) of the results:
    // fused planes, the unpacked frame of a scoring plan, backgrounds, image.
    const double samples = double(cfg.sensors) * cfg.channels * cfg.height * cfg.width;
    const double frame_bytes = cfg.input == PixelType::U8 ? 1 : 4;
    return std::max(samples * cfg.frames * frame_bytes, samples * 4);
}

std::uint32_t sensors_per_binding(std::uint32_t sensors, double bytes_per_sensor,
                                  std::span<const std::uint64_t> strides, std::uint64_t range_bytes,
                                  std::uint64_t offset_alignment) {
    const double range = double(range_bytes);
    if (bytes_per_sensor * sensors <= range) return sensors;
    const auto fit = std::uint64_t(std::floor(range / bytes_per_sensor));
    // Block b starts at b * n * stride in each buffer: n a multiple of
    // alignment / gcd(stride, alignment) keeps that a multiple of alignment.
    const std::uint64_t alignment = std::max<std::uint64_t>(offset_alignment, 4);
    std::uint64_t step = 1;
    for (std::uint64_t stride : strides) step = std::lcm(step, alignment / std::gcd(stride, alignment));
    return std::uint32_t(std::min<std::uint64_t>(fit / step * step, sensors));
}

}  // namespace vkfuse::vk

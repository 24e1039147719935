// The plan's graph-building helpers (vk/plan_impl.hpp): buffers, spans, the
// frames as uploaded and, on request, unpacked into planes.
#include <cstring>
#include <optional>

#include "vk/plan_impl.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

VkDeviceAddress GraphBuilder::floats(std::uint64_t count) {
    buffers.emplace_back(ctx, count * sizeof(float), MemoryUse::Device);
    return buffers.back().address();
}

VkDeviceAddress GraphBuilder::planes(std::uint64_t count) {
    const std::uint64_t bytes_per_sample = cfg.precision == Precision::Fp16Storage ? 2 : 4;
    // Rounded up to whole floats: a float16 plane set of odd length stays 4-byte sized.
    buffers.emplace_back(ctx, (count * bytes_per_sample + 3) / 4 * 4, MemoryUse::Device);
    return buffers.back().address();
}

DeviceSpan GraphBuilder::span(VkDeviceAddress address, VkDeviceSize bytes) const {
    auto within = [&](const Buffer& b) -> std::optional<DeviceSpan> {
        if (!b.handle() || address < b.address() || address >= b.address() + b.size()) return std::nullopt;
        const VkDeviceSize from = address - b.address();
        if (bytes > b.size() - from) throw Error(ErrorKind::Device, "internal: span past the end of its buffer");
        return b.span().sub(from, bytes);
    };
    for (const Buffer& b : buffers)
        if (auto s = within(b)) return *s;
    for (const Buffer* b : fixed)
        if (auto s = within(*b)) return *s;
    throw Error(ErrorKind::Device, "internal: no plan buffer holds the address");
}

double largest_buffer_bytes(const PlanConfig& c) {
    // The largest buffers: the frames as uploaded, and one plane set of every
    // frame (a periodization block is up to one sample wider and taller).
    return double(c.sensors) * c.frames * c.channels * (double(c.height) + 1) * (double(c.width) + 1) * 4;
}

bool needs_device_addresses(const PlanConfig& c, const VkPhysicalDeviceLimits& limits) {
    return largest_buffer_bytes(c) > double(limits.maxStorageBufferRange);
}

PushConstants FrameSource::frame_fields() const {
    return PushConstants()
        .u32(std::uint32_t(g_.cfg.width) * std::uint32_t(g_.cfg.height))
        .u32(std::uint32_t(g_.cfg.channels))
        .u32(g_.cfg.input == PixelType::U8);
}

VkDeviceAddress FrameSource::planes() {
    if (planes_) return planes_;
    const std::uint32_t pixels = std::uint32_t(g_.cfg.width) * std::uint32_t(g_.cfg.height);
    const bool quads = pixels % 4 == 0;  // four pixels per invocation
    const Grid grid = grid_1d(quads ? pixels / 4 : pixels, 256);
    planes_ = g_.planes(std::uint64_t(g_.planes_in()) * pixels);
    const DeviceSpan out = g_.span(planes_);
    g_.rec.dispatch("unpack", {frames_, frames_, out, out}, frame_fields().u32(quads), grid.x, grid.y,
                    std::uint32_t(g_.cfg.sensors * g_.cfg.frames));
    g_.rec.mark("unpack");
    return planes_;
}

VkDeviceAddress GraphBuilder::constants(const std::vector<float>& values) {
    buffers.emplace_back(ctx, values.size() * sizeof(float), MemoryUse::Upload);
    std::memcpy(buffers.back().mapped(), values.data(), values.size() * sizeof(float));
    return buffers.back().address();
}

}  // namespace vkfuse::vk

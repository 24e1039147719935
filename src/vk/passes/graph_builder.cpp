// The plan's graph-building helpers (vk/passes/graph.hpp): buffers, spans, the
// frames as uploaded and, on request, unpacked into planes.
#include <cstring>
#include <optional>

#include "vk/passes/graph.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

Buffer& GraphBuilder::intermediate(VkDeviceSize bytes, MemoryUse use) {
    if (!reuse_from) return buffers.emplace_back(ctx, bytes, use);
    // A later block has as many sensors as the first or fewer, and the same
    // graph: the same requests in the same order, none larger.
    if (*reuse_from >= buffers.size() || buffers[*reuse_from].size() < bytes)
        throw Error(ErrorKind::Device, "internal: a block of sensors records other intermediates than the first");
    return buffers[(*reuse_from)++];
}

VkDeviceAddress GraphBuilder::floats(std::uint64_t count) {
    return intermediate(count * sizeof(float), MemoryUse::Device).address();
}

VkDeviceAddress GraphBuilder::planes(std::uint64_t count) {
    const std::uint64_t bytes_per_sample = cfg.precision == Precision::Fp16Storage ? 2 : 4;
    // Rounded up to whole floats: a float16 plane set of odd length stays 4-byte sized.
    return intermediate((count * bytes_per_sample + 3) / 4 * 4, MemoryUse::Device).address();
}

DeviceSpan GraphBuilder::span(VkDeviceAddress address, VkDeviceSize bytes) const {
    auto within = [&](const DeviceSpan& b) -> std::optional<DeviceSpan> {
        if (!b.buffer || address < b.address() || address >= b.address() + b.bytes) return std::nullopt;
        const VkDeviceSize from = address - b.address();
        if (bytes > b.bytes - from) throw Error(ErrorKind::Device, "internal: span past the end of its buffer");
        return b.sub(from, bytes);
    };
    for (const Buffer& b : buffers)
        if (auto s = within(b.span())) return *s;
    for (const DeviceSpan& b : fixed)
        if (auto s = within(b)) return *s;
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
        .u32("pixels", std::uint32_t(g_.cfg.width) * std::uint32_t(g_.cfg.height))
        .u32("channels", std::uint32_t(g_.cfg.channels))
        .u32("is_u8", g_.cfg.input == PixelType::U8);
}

VkDeviceAddress FrameSource::planes() {
    if (planes_) return planes_;
    const std::uint32_t pixels = std::uint32_t(g_.cfg.width) * std::uint32_t(g_.cfg.height);
    const bool quads = pixels % 4 == 0;  // four pixels per invocation
    planes_ = g_.planes(std::uint64_t(g_.planes_in()) * pixels);
    const DeviceSpan out = g_.span(planes_);
    g_.rec.dispatch("unpack", {frames_, frames_, out, out}, frame_fields().u32("quads", quads),
                    Recorder::LinearWork{quads ? pixels / 4 : pixels, std::uint32_t(g_.cfg.sensors * g_.cfg.frames)});
    g_.rec.mark("unpack");
    return planes_;
}

VkDeviceAddress GraphBuilder::constants(const std::vector<float>& values) {
    const std::size_t bytes = values.size() * sizeof(float);
    const bool reused = reuse_from.has_value();
    Buffer& b = intermediate(bytes, MemoryUse::Upload);
    // The first block's dispatches read these values too: a later block
    // shares them, never rewrites them.
    if (reused && std::memcmp(b.mapped(), values.data(), bytes) != 0)
        throw Error(ErrorKind::Device, "internal: a block of sensors records other constants than the first");
    if (!reused) std::memcpy(b.mapped(), values.data(), bytes);
    return b.address();
}

}  // namespace vkfuse::vk

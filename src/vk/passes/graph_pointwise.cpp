// Brovey, channel-sum and the mean: one kernel from the frames as uploaded to
// the fused planes and the read-back image, each output pixel from its K inputs.
#include "vk/passes/graph.hpp"

namespace vkfuse::vk {

VkDeviceAddress record_pointwise(GraphBuilder& g, DeviceSpan frames, std::optional<DeviceSpan> image,
                                 std::uint32_t kernel, const char* stage) {
    const std::uint32_t pixels = std::uint32_t(g.cfg.width) * std::uint32_t(g.cfg.height);
    const VkDeviceAddress out = g.planes(std::uint64_t(g.planes_out()) * pixels);
    const bool quads = pixels % 4 == 0;
    const DeviceSpan planes = g.span(out), img = image ? *image : planes;
    g.rec.dispatch(
        "pointwise_fuse",
        {frames, frames, planes, planes, img, img, g.brovey_thresholds ? g.span(g.brovey_thresholds) : planes},
        PushConstants()
            .u32("pixels", pixels)
            .u32("channels", std::uint32_t(g.cfg.channels))
            .u32("is_u8", g.cfg.input == PixelType::U8)
            .u32("scaled_threshold", g.brovey_thresholds ? 1 : 0)
            .u32("quads", quads)
            .u32("write_planes", !g.cfg.metrics.empty())
            .u32("write_image", image.has_value()),
        Recorder::LinearWork{quads ? pixels / 4 : pixels, std::uint32_t(g.cfg.sensors)},
        std::array<std::uint32_t, 2>{kernel, std::uint32_t(g.cfg.frames)});  // METHOD and FRAMES
    g.rec.mark(stage);
    return out;
}

}  // namespace vkfuse::vk

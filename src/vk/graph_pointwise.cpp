// Brovey, channel-sum and the mean: one kernel, each output pixel from its K inputs.
#include "vk/plan_impl.hpp"

namespace vkfuse::vk {

VkDeviceAddress record_pointwise(GraphBuilder& g, VkDeviceAddress input) {
    const std::uint32_t pixels = std::uint32_t(g.cfg.width) * std::uint32_t(g.cfg.height);
    const VkDeviceAddress out = g.planes(std::uint64_t(g.planes_out()) * pixels);
    const bool quads = pixels % 4 == 0;
    const Grid grid = grid_1d(quads ? pixels / 4 : pixels, 256);
    const Method method = g.cfg.fusion.method;
    const std::uint32_t kernel_method = method == Method::Mean ? 2 : method == Method::ChannelSum ? 1 : 0;
    const DeviceSpan src = g.span(input), dst = g.span(out);
    g.rec.dispatch("pointwise_fuse", {src, src, dst, dst, g.brovey_thresholds ? g.span(g.brovey_thresholds) : src},
                   PushConstants()
                       .u32(pixels)
                       .u32(std::uint32_t(g.cfg.frames))
                       .u32(std::uint32_t(g.cfg.channels))
                       .u32(kernel_method)
                       .u32(g.brovey_thresholds ? 1 : 0)
                       .u32(quads),
                   grid.x, grid.y, g.planes_out());
    g.rec.mark(method == Method::Mean ? "mean" : method == Method::ChannelSum ? "channel_sum" : "brovey");
    return out;
}

}  // namespace vkfuse::vk

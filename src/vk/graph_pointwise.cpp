// Brovey, channel-sum and the mean: one kernel, each output pixel from its K inputs.
#include "vk/plan_impl.hpp"

namespace vkfuse::vk {

VkDeviceAddress record_pointwise(GraphBuilder& g, VkDeviceAddress input) {
    const std::uint32_t pixels = std::uint32_t(g.cfg.width) * std::uint32_t(g.cfg.height);
    const VkDeviceAddress out = g.planes(std::uint64_t(g.planes_out()) * pixels);
    const Grid grid = grid_1d(pixels, 256);
    const Method method = g.cfg.fusion.method;
    const std::uint32_t kernel_method = method == Method::Mean ? 2 : method == Method::ChannelSum ? 1 : 0;
    g.rec.dispatch("pointwise_fuse",
                   PushConstants()
                       .ptr(input)
                       .ptr(out)
                       .u32(pixels)
                       .u32(std::uint32_t(g.cfg.frames))
                       .u32(std::uint32_t(g.cfg.channels))
                       .u32(kernel_method)
                       .ptr(g.brovey_thresholds ? g.brovey_thresholds : input)
                       .u32(g.brovey_thresholds ? 1 : 0),
                   grid.x, grid.y, g.planes_out());
    g.rec.mark(method == Method::Mean ? "mean" : method == Method::ChannelSum ? "channel_sum" : "brovey");
    return out;
}

}  // namespace vkfuse::vk

// Brovey and channel-sum: one kernel, each output pixel from its K inputs.
#include "vk/plan_impl.hpp"

namespace vkfuse::vk {

VkDeviceAddress record_pointwise(GraphBuilder& g, VkDeviceAddress input) {
    const std::uint32_t pixels = std::uint32_t(g.cfg.width) * std::uint32_t(g.cfg.height);
    const VkDeviceAddress out = g.floats(std::uint64_t(g.planes_out()) * pixels);
    const Grid grid = grid_1d(pixels, 256);
    const bool channel_sum = g.cfg.fusion.method == Method::ChannelSum;
    g.rec.dispatch("pointwise_fuse",
                   PushConstants()
                       .ptr(input)
                       .ptr(out)
                       .u32(pixels)
                       .u32(std::uint32_t(g.cfg.frames))
                       .u32(std::uint32_t(g.cfg.channels))
                       .u32(channel_sum ? 1 : 0),
                   grid.x, grid.y, g.planes_out());
    g.rec.mark(channel_sum ? "channel_sum" : "brovey");
    return out;
}

}  // namespace vkfuse::vk

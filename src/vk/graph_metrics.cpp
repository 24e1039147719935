// Sharpness, RMS contrast and background difference as a two-pass hierarchical
// reduction: per-workgroup partials, one final workgroup per sensor, then the
// contrast pass that needs the mean, reduced the same way.
#include "vk/plan_impl.hpp"

namespace vkfuse::vk {

void record_metrics(GraphBuilder& g, VkDeviceAddress fused, VkDeviceAddress background, VkDeviceAddress totals0,
                    VkDeviceAddress totals1) {
    // metrics_partial.comp: WG invocations per group, each ROWS pixels of one column.
    constexpr std::uint32_t kGroupSize = 256, kRows = 16;
    const std::uint64_t items = std::uint64_t(g.cfg.width) * groups(std::uint64_t(g.cfg.height), kRows);
    const std::uint32_t wgs = groups(items, kGroupSize);
    const Grid grid = grid_1d(wgs, 1);
    const std::uint32_t S = std::uint32_t(g.cfg.sensors);
    const VkDeviceAddress partials = g.floats(std::uint64_t(wgs) * S * 4);
    for (std::uint32_t pass = 0; pass < 2; ++pass) {
        const VkDeviceAddress totals = pass == 0 ? totals0 : totals1;
        g.rec.dispatch("metrics_partial",
                       PushConstants()
                           .ptr(fused)
                           .ptr(background ? background : fused)
                           .ptr(partials)
                           .ptr(totals0)
                           .i32(g.cfg.width)
                           .i32(g.cfg.height)
                           .u32(std::uint32_t(g.cfg.channels))
                           .u32(wgs)
                           .u32(background ? 1 : 0)
                           .u32(pass),
                       grid.x, grid.y, S);
        g.rec.dispatch("reduce_partials", PushConstants().ptr(partials).ptr(totals).u32(wgs), 1, 1, S);
    }
    g.rec.mark("metrics");
}

}  // namespace vkfuse::vk

// Laplacian pyramid fusion (docs/spec.md): pyrDown chain per frame, level-by-level
// fusion of G_l - pyrUp(G_{l+1}) (the Laplacian coefficient is formed inside
// the fusion kernel, never stored), then collapse from the top, in place.
#include <span>
#include <vector>

#include "vk/passes/graph.hpp"

namespace vkfuse::vk {
namespace {

struct Level {
    std::uint32_t w, h;
    VkDeviceAddress gauss;  // G_l of every frame: S*K*C planes
    VkDeviceAddress fused;  // C_l, then R_l: S*C planes
};



constexpr std::uint32_t kPyrDownRows = VKFUSE_PYR_DOWN_ROWS;
constexpr std::uint32_t kLapFuseRows = VKFUSE_LAP_FUSE_ROWS;
constexpr std::uint32_t kLapCollapseRows = VKFUSE_LAP_COLLAPSE_ROWS;

// The pyramid's level sizes; lv[0].gauss is the caller's.
std::vector<Level> level_sizes(const PlanConfig& cfg) {
    std::vector<Level> lv(std::size_t(cfg.fusion.effective_levels()) + 1);
    lv[0] = {std::uint32_t(cfg.width), std::uint32_t(cfg.height), 0, 0};
    for (std::size_t l = 1; l < lv.size(); ++l) lv[l] = {(lv[l - 1].w + 1) / 2, (lv[l - 1].h + 1) / 2, 0, 0};
    return lv;
}

// G_1 .. G_L of every frame from G_0.
void pyr_down_chain(GraphBuilder& g, std::vector<Level>& lv) {
    for (std::size_t l = 1; l < lv.size(); ++l) {
        auto& p = lv[l - 1];
        auto& c = lv[l];
        c.gauss = g.planes(std::uint64_t(g.planes_in()) * c.w * c.h);
        // Where the source rows are whole pairs of quads, 4 QUADS outputs per
        // invocation from 2 QUADS + 2 plane4 loads a source row: two quads
        // where the rows allow (6 loads for 8 outputs instead of 8).
        if (p.w % 8 == 0) {
            const std::uint32_t quads = p.w % 16 == 0 ? 2 : 1;
            const std::uint32_t spec[] = {quads};
            g.rec.dispatch(
                "pyr_down4", {g.span(p.gauss), g.span(c.gauss)},
                PushConstants().i32("sw", int(p.w)).i32("sh", int(p.h)).i32("dw", int(c.w)).i32("dh", int(c.h)),
                Recorder::Work{c.w / (4 * quads), groups(c.h, kPyrDownRows), g.planes_in()}, spec);
            continue;
        }
        g.rec.dispatch("pyr_down", {g.span(p.gauss), g.span(c.gauss)},
                       PushConstants().i32("sw", int(p.w)).i32("sh", int(p.h)).i32("dw", int(c.w)).i32("dh", int(c.h)),
                       Recorder::Work{c.w, groups(c.h, kPyrDownRows), g.planes_in()});
    }
    g.rec.mark("pyr_down");
}

// Every frame's G_0 .. G_L as the planes a cache keeps.
std::vector<PlaneView> levels_of(const std::vector<Level>& lv) {
    std::vector<PlaneView> out;
    for (const Level& l : lv) out.push_back({l.gauss, int(l.w), l.w * l.h});
    return out;
}

// Each level's fusion across the frames, one dispatch per group of sources,
// then the collapse from the top, in place; returns the fused planes. A plan
// (period 0) has one group, its own pyramids, fused for every sensor; a cache
// has its groups' pyramids, fused for sensors in blocks of `period` sources,
// frames named by the table.
VkDeviceAddress fuse_and_collapse(GraphBuilder& g, std::vector<Level>& lv, std::span<const CachedSources> from,
                                  std::uint32_t period, std::optional<DeviceSpan> table) {
    const std::size_t L = lv.size() - 1;
    for (std::size_t l = 0; l <= L; ++l) {
        auto& c = lv[l];
        c.fused = g.planes(std::uint64_t(g.planes_out()) * c.w * c.h);
    }
    for (const CachedSources& sources : from) {
        const SensorGroup group = period ? SensorGroup{sources.first, sources.count, period} : SensorGroup{};
        for (std::size_t l = 0; l <= L; ++l) {
            const auto& c = lv[l];
            const VkDeviceAddress gauss = sources.levels[l].addr;
            if (l == L) {  // the base rule on G_L itself
                const PlaneView top_in{gauss, int(c.w), c.w * c.h}, top_out{c.fused, int(c.w), c.w * c.h};
                record_rule_fuse(g, {top_in, top_out, int(c.w), int(c.h), int(c.w), int(c.h), table, 0, 0, group});
                continue;
            }
            // The detail rule on G_l - pyrUp(G_{l+1}); both kernels take the
            // same scalars, and the rule as their specialization constant 0.
            const Level& coarse = lv[l + 1];
            const PushConstants scalars = PushConstants()
                                              .i32("width", int(c.w))
                                              .i32("height", int(c.h))
                                              .i32("cw", int(coarse.w))
                                              .i32("ch", int(coarse.h))
                                              .u32("frames", std::uint32_t(g.cfg.frames))
                                              .u32("channels", std::uint32_t(g.cfg.channels))
                                              .u32("use_table", table ? 1 : 0)
                                              .append(group.push(g.cfg));
            const std::uint32_t rule[] = {rule_code(g.cfg.fusion.detail_rule)};
            const DeviceSpan src = g.span(gauss), up = g.span(sources.levels[l + 1].addr), dst = g.span(c.fused);
            const DeviceSpan frames = table ? *table : src;
            if (c.w % 8 == 0)  // 2 x 8 outputs per invocation and coarse row, plane4 loads and stores
                g.rec.dispatch("lap_fuse4", {src, up, up, dst, frames}, scalars,
                               Recorder::Work{coarse.w / 4, groups(coarse.h, kLapFuseRows), group.planes(g.cfg)}, rule);
            else  // 2 x 2 outputs per invocation
                g.rec.dispatch("lap_fuse", {src, up, dst, frames}, scalars,
                               Recorder::Work{coarse.w, coarse.h, group.planes(g.cfg)}, rule);
        }
    }
    g.rec.mark("lap_fuse");
    for (std::size_t i = L; i-- > 0;) {
        auto& c = lv[i];
        auto& up = lv[i + 1];
        if (c.w % 8 == 0) {
            const DeviceSpan coarse = g.span(up.fused);
            g.rec.dispatch("lap_collapse4", {coarse, coarse, g.span(c.fused)},
                           PushConstants()
                               .i32("width", int(c.w))
                               .i32("height", int(c.h))
                               .i32("cw", int(up.w))
                               .i32("ch", int(up.h)),
                           Recorder::Work{up.w / 4, groups(up.h, kLapCollapseRows), g.planes_out()});
            continue;
        }
        g.rec.dispatch(
            "lap_collapse", {g.span(up.fused), g.span(c.fused)},
            PushConstants().i32("width", int(c.w)).i32("height", int(c.h)).i32("cw", int(up.w)).i32("ch", int(up.h)),
            Recorder::Work{up.w, up.h, g.planes_out()});
    }
    g.rec.mark("lap_collapse");
    return lv[0].fused;
}

}  // namespace

// Level 0's two readers (the first pyrDown and level 0's fusion) read the
// unpacked planes: reading the frames as uploaded instead, every channel of a
// frame per invocation as dwt_rows_frames does, costs more on lavapipe than
// the unpack pass it saves (docs/architecture.md has the figures).
VkDeviceAddress record_laplacian(GraphBuilder& g, FrameSource& frames) {
    std::vector<Level> lv = level_sizes(g.cfg);
    lv[0].gauss = frames.planes();
    pyr_down_chain(g, lv);
    const CachedSources own{0, std::uint32_t(g.cfg.sensors), levels_of(lv)};
    return fuse_and_collapse(g, lv, {&own, 1}, 0, std::nullopt);
}

std::vector<PlaneView> record_laplacian_decompose(GraphBuilder& g, FrameSource& frames) {
    std::vector<Level> lv = level_sizes(g.cfg);
    lv[0].gauss = frames.planes();
    pyr_down_chain(g, lv);
    return levels_of(lv);
}

VkDeviceAddress record_laplacian_cached(GraphBuilder& g, std::span<const CachedSources> groups, std::uint32_t sources,
                                        DeviceSpan table) {
    std::vector<Level> lv = level_sizes(g.cfg);
    return fuse_and_collapse(g, lv, groups, sources, table);
}

}  // namespace vkfuse::vk

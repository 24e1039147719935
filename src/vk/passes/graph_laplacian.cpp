// Laplacian pyramid fusion (docs/spec.md): pyrDown chain per frame, then from
// the top level down, each level's fusion of G_l - pyrUp(G_{l+1}) and its
// collapse (the Laplacian coefficient is formed inside the fusion kernel,
// never stored; where a level's rows are whole pairs of quads, neither is the
// fused detail).
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
                Recorder::LinearWork{std::uint64_t(c.w / (4 * quads)) * groups(c.h, kPyrDownRows), g.planes_in()}, spec);
            continue;
        }
        g.rec.dispatch("pyr_down", {g.span(p.gauss), g.span(c.gauss)},
                       PushConstants().i32("sw", int(p.w)).i32("sh", int(p.h)).i32("dw", int(c.w)).i32("dh", int(c.h)),
                       Recorder::LinearWork{std::uint64_t(c.w) * groups(c.h, kPyrDownRows), g.planes_in()});
    }
    g.rec.mark("pyr_down");
}

// Every frame's G_0 .. G_L as the planes a cache keeps.
std::vector<PlaneView> levels_of(const std::vector<Level>& lv) {
    std::vector<PlaneView> out;
    for (const Level& l : lv) out.push_back({l.gauss, int(l.w), l.w * l.h});
    return out;
}

// The scalars lap_fuse and lap_fuse_collapse4 take at level l.
PushConstants level_scalars(const GraphBuilder& g, const Level& c, const Level& coarse, bool table,
                            const SensorGroup& group) {
    return PushConstants()
        .i32("width", int(c.w))
        .i32("height", int(c.h))
        .i32("cw", int(coarse.w))
        .i32("ch", int(coarse.h))
        .u32("frames", std::uint32_t(g.cfg.frames))
        .u32("channels", std::uint32_t(g.cfg.channels))
        .u32("use_table", table ? 1 : 0)
        .append(group.push(g.cfg));
}

// Levels whose rows are whole pairs of quads fuse and collapse in one pass
// (lap_fuse_collapse4); the others fuse (lap_fuse), then collapse
// (lap_collapse).
bool fused_with_collapse(const Level& l) { return l.w % 8 == 0; }

// Each level's fusion across the frames and the collapse from the top;
// returns the fused planes. A plan (period 0) has one group, its own
// pyramids, fused for every sensor; a cache has its groups' pyramids, fused
// for sensors in blocks of `period` sources, frames named by the table.
//
//   G_L -> [rule_fuse] -> R_L                       (the base rule)
//   G_l -> [lap_fuse] -> C_l                        (levels of other widths; independent of one another)
//   for l = L-1 .. 0:
//     G_l, G_{l+1}, R_{l+1} -> [lap_fuse_collapse4] -> R_l
//     or C_l, R_{l+1} -> [lap_collapse] -> R_l (C_l in place)
VkDeviceAddress fuse_and_collapse(GraphBuilder& g, std::vector<Level>& lv, std::span<const CachedSources> from,
                                  std::uint32_t period, std::optional<DeviceSpan> table) {
    const std::size_t L = lv.size() - 1;
    for (std::size_t l = 0; l <= L; ++l) {
        auto& c = lv[l];
        c.fused = g.planes(std::uint64_t(g.planes_out()) * c.w * c.h);
    }
    const std::uint32_t rule[] = {rule_code(g.cfg.fusion.detail_rule)};
    auto group_of = [&](const CachedSources& sources) {
        return period ? SensorGroup{sources.first, sources.count, period} : SensorGroup{};
    };
    for (const CachedSources& sources : from) {
        const SensorGroup group = group_of(sources);
        const Level& top = lv[L];
        const PlaneView top_in{sources.levels[L].addr, int(top.w), top.w * top.h};
        const PlaneView top_out{top.fused, int(top.w), top.w * top.h};
        record_rule_fuse(g, {top_in, top_out, int(top.w), int(top.h), int(top.w), int(top.h), table, 0, 0, group});
        for (std::size_t l = 0; l < L; ++l) {
            if (fused_with_collapse(lv[l])) continue;
            const DeviceSpan src = g.span(sources.levels[l].addr);
            g.rec.dispatch("lap_fuse",
                           {src, g.span(sources.levels[l + 1].addr), g.span(lv[l].fused), table ? *table : src},
                           level_scalars(g, lv[l], lv[l + 1], table.has_value(), group),
                           Recorder::LinearWork{std::uint64_t(lv[l + 1].w) * lv[l + 1].h, group.planes(g.cfg)}, rule);
        }
    }
    g.rec.mark("lap_fuse");
    bool any_fused = false;
    for (std::size_t l = L; l-- > 0;) {
        const Level& c = lv[l];
        const Level& up = lv[l + 1];
        const DeviceSpan residual = g.span(up.fused);
        if (!fused_with_collapse(c)) {
            g.rec.dispatch(
                "lap_collapse", {residual, g.span(c.fused)},
                PushConstants().i32("width", int(c.w)).i32("height", int(c.h)).i32("cw", int(up.w)).i32("ch", int(up.h)),
                Recorder::LinearWork{std::uint64_t(up.w) * up.h, g.planes_out()});
            continue;
        }
        any_fused = true;
        for (const CachedSources& sources : from) {
            const SensorGroup group = group_of(sources);
            const DeviceSpan src = g.span(sources.levels[l].addr), coarse = g.span(sources.levels[l + 1].addr);
            g.rec.dispatch("lap_fuse_collapse4", {src, coarse, coarse, residual, residual, g.span(c.fused),
                                                  table ? *table : src},
                           level_scalars(g, c, up, table.has_value(), group),
                           Recorder::LinearWork{std::uint64_t(up.w / 4) * groups(up.h, kLapFuseRows), group.planes(g.cfg)},
                           rule);
        }
    }
    g.rec.mark(any_fused ? "lap_fuse_collapse" : "lap_collapse");
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

// rule_fuse.comp over one region of every plane: the fusion rules applied
// coefficient by coefficient across the K frames, shared by the Laplacian
// top level and the symmetric wavelet levels.
#include "vk/passes/graph.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

PushConstants SensorGroup::push(const PlanConfig& cfg) const {
    const SensorGroup w = in(cfg);
    if (w.first + w.count > w.period || cfg.sensors % int(w.period) != 0)
        throw Error(ErrorKind::Device, "internal: a sensor group outside its plan's sensors");
    return PushConstants().u32("group_first", w.first).u32("group_count", w.count).u32("group_period", w.period);
}

std::uint32_t SensorGroup::planes(const PlanConfig& cfg) const {
    const SensorGroup w = in(cfg);
    return std::uint32_t(cfg.sensors) / w.period * w.count * std::uint32_t(cfg.channels);
}

void record_rule_fuse(GraphBuilder& g, const RuleFuseRegion& r) {
    if (r.src.row_stride != r.dst.row_stride || r.src.plane_stride != r.dst.plane_stride)
        throw Error(ErrorKind::Device, "internal: rule_fuse takes one set of strides for its source and result");
    const FusionSpec& spec = g.cfg.fusion;
    const DeviceSpan src = g.span(r.src.addr), dst = g.span(r.dst.addr);
    const bool quads = r.width % 4 == 0 && r.src.row_stride % 4 == 0 && r.src.plane_stride % 4 == 0;
    g.rec.dispatch("rule_fuse", {src, dst, r.table ? *r.table : src, src, dst},
                   PushConstants()
                       .i32("width", r.width)
                       .i32("height", r.height)
                       .i32("row_stride", r.src.row_stride)
                       .u32("plane_stride", r.src.plane_stride)
                       .u32("frames", std::uint32_t(g.cfg.frames))
                       .u32("channels", std::uint32_t(g.cfg.channels))
                       .u32("base_rule", rule_code(spec.base_rule))
                       .u32("detail_rule", rule_code(spec.detail_rule))
                       .i32("split_w", r.split_w)
                       .i32("split_h", r.split_h)
                       .u32("use_table", r.table ? 1 : 0)
                       .i32("skip_w", r.skip_w)
                       .i32("skip_h", r.skip_h)
                       .u32("quads", quads)
                       .append(r.group.push(g.cfg)),
                   Recorder::LinearWork{std::uint64_t(quads ? r.width / 4 : r.width) * std::uint64_t(r.height),
                                        r.group.planes(g.cfg)});
}

}  // namespace vkfuse::vk

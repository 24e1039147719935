#include "study/cached_fusion.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "vk/engine/command_slot.hpp"
#include "vk/engine/context_impl.hpp"
#include "vk/passes/graph.hpp"
#include "vk/engine/magnitude.hpp"
#include "vk/plan/method_recorders.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

// Fused sensors per cycle: enough that the small deep levels' dispatches
// fill the device, few enough that a batch's planes stay modest (40 sensors
// of QVGA RGB: about 90 MiB of intermediates).
constexpr int kSensorsPerCycle = 40;
// Recorded cycles kept: a study walks the combination sizes in turn; its
// greedy search asks for one size per step.
constexpr std::size_t kGraphsKept = 4;

PlanConfig base_config(const CachedFusionShape& s) {
    PlanConfig c;
    c.fusion = s.fusion;
    c.height = s.height;
    c.width = s.width;
    c.channels = s.channels;
    c.want_fused = false;
    c.metrics = MetricSet::all();
    return c;
}

// The frames (source-major) of cfg.sensors sources from `first` on,
// decomposed in one submit; the buffers holding the levels move into `keep`.
CachedSources decompose(Context::Impl& ctx, const PlanConfig& cfg, std::uint32_t first,
                        std::span<const FrameView> images, std::vector<Buffer>& keep) {
    // Every frame of the group in one submit, as float32: 8-bit ones divided
    // by 255 here as frames.glsl would (one correctly rounded division either way).
    const std::uint64_t frame_floats = std::uint64_t(cfg.height) * cfg.width * cfg.channels;
    Buffer upload(ctx, frame_floats * images.size() * 4, MemoryUse::Upload);
    auto* dst = static_cast<float*>(upload.mapped());
    for (const FrameView& v : images) {
        if (v.type == PixelType::F32) {
            std::memcpy(dst, v.data, frame_floats * 4);
        } else {
            const auto* bytes = static_cast<const std::uint8_t*>(v.data);
            for (std::uint64_t i = 0; i < frame_floats; ++i) dst[i] = float(bytes[i]) / 255.0f;
        }
        dst += frame_floats;
    }
    std::vector<Buffer> buffers;
    CachedSources group{first, std::uint32_t(cfg.sensors), {}};
    {
        DescriptorSets sets(ctx);
        CommandSlot slot(ctx, 0);
        Recorder rec(ctx, slot.recording_target(), slot.queries(), "", sets,
                     ctx.device_addresses_only || needs_device_addresses(cfg, ctx.properties.limits));
        GraphBuilder g{ctx, cfg, rec, buffers, 0, {upload.span()}};
        FrameSource input(g, upload.span());
        group.levels = method_recorder(cfg.fusion.method).decompose(g, input);
        rec.finish();
        slot.submit_and_wait();
    }
    for (Buffer& b : buffers)
        if (std::any_of(group.levels.begin(), group.levels.end(),
                        [&](const PlaneView& v) { return v.addr >= b.address() && v.addr < b.address() + b.size(); }))
            keep.push_back(std::move(b));
    return group;
}

}  // namespace

// The coefficient cache: the buffers of the decompositions that hold their
// levels (their scratch dropped), and per group of sources the levels as the
// method's recorders view them.
struct CachedFusion::Cache {
    std::vector<Buffer> buffers;
    // Consecutive sources, every group but the last of the first one's size.
    std::vector<CachedSources> groups;
};

// One recorded cycle for combinations of k frames: batch() combinations of
// every source at once.
struct CachedFusion::Graph {
    std::size_t k = 0;
    PlanConfig cfg;  // sensors: batch() x sources fused, frames: k
    Buffer table;    // host-written: sensor j's k frames in the cache
    Buffer readback;
    std::vector<Buffer> buffers;
    std::optional<DescriptorSets> sets;
    std::optional<CommandSlot> slot;  // last: released (and waited out) first
};

std::uint64_t CachedFusion::cache_bytes(const CachedFusionShape& s) {
    // At its peak the decomposition holds the frames as uploaded (float32),
    // their unpacked planes, a wavelet's row scratch and its levels (4/3 of
    // the frames, a little more where periodization pads): under five times
    // the frames' float32 size.
    return 5 * std::uint64_t(s.sources) * std::uint64_t(s.frames) * std::uint64_t(s.channels) *
           std::uint64_t(s.height) * std::uint64_t(s.width) * 4;
}

bool CachedFusion::supports(Method method) { return method_recorder(method).caches_coefficients(); }

CachedFusion::CachedFusion(Context& context, const CachedFusionShape& shape, std::span<const FrameView> images)
    : ctx_(ContextAccess::of(context)), shape_(shape), cache_(std::make_unique<Cache>()) {
    if (!supports(shape.fusion.method))
        throw Error(ErrorKind::InvalidArgument, "cached fusion: " + std::string(to_string(shape.fusion.method)) +
                                                    " has no coefficients to fuse from (its Vulkan row decomposes nothing)");
    if (shape.sources < 2 || shape.frames < 2)
        throw Error(ErrorKind::InvalidArgument, "cached fusion: needs a background and a source, and two frames each");
    if (images.size() != std::size_t(shape.sources) * std::size_t(shape.frames))
        throw Error(ErrorKind::InvalidArgument, "cached fusion: got " + std::to_string(images.size()) +
                                                    " images for " + std::to_string(shape.sources) + " sources x " +
                                                    std::to_string(shape.frames) + " frames");
    validate(shape.fusion, shape.height, shape.width, shape.channels, 2);
    for (std::size_t i = 0; i < images.size(); ++i) {
        const FrameView& v = images[i];
        if (v.height != shape.height || v.width != shape.width || v.channels != shape.channels)
            throw Error(ErrorKind::InvalidArgument, "cached fusion: frame " + std::to_string(i % shape.frames) +
                                                        " of source " + std::to_string(i / shape.frames) +
                                                        " is not " + std::to_string(shape.width) + "x" +
                                                        std::to_string(shape.height) + "x" +
                                                        std::to_string(shape.channels));
    }
    // Sources are decomposed in groups whose buffers one descriptor binds
    // whole, so that the cycles' kernels reach the cache through bindings
    // (the cheaper way to memory: bindings.glsl). Where not even one
    // source's frames fit, one group of every source, reached through
    // device addresses.
    PlanConfig cfg = base_config(shape);
    cfg.sensors = 1;
    cfg.frames = shape.frames;
    cfg.metrics = {};
    cfg.input = PixelType::F32;
    const double binding = double(shape.max_binding_bytes ? std::min<std::uint64_t>(shape.max_binding_bytes,
                                                                                  ctx_.properties.limits.maxStorageBufferRange)
                                                          : ctx_.properties.limits.maxStorageBufferRange);
    const double per_source = largest_buffer_bytes(cfg);
    const int fit = per_source <= binding ? int(std::min<double>(shape.sources, std::floor(binding / per_source))) : 0;
    const int group_size = fit > 0 ? fit : shape.sources;
    for (int first = 0; first < shape.sources; first += group_size) {
        const int count = std::min(group_size, shape.sources - first);
        cfg.sensors = count;
        const std::size_t from = std::size_t(first) * std::size_t(shape.frames);
        cache_->groups.push_back(decompose(ctx_, cfg, std::uint32_t(first),
                                           images.subspan(from, std::size_t(count) * std::size_t(shape.frames)),
                                           cache_->buffers));
    }
    // A cycle's largest buffer: one plane set of its fused sensors (as a
    // plan's of that many sensors and one frame).
    PlanConfig fused = base_config(shape);
    fused.sensors = int(batch()) * shape.sources;
    fused.frames = 1;
    addressed_ = ctx_.device_addresses_only || fit == 0 || needs_device_addresses(fused, ctx_.properties.limits);
}

CachedFusion::~CachedFusion() = default;

std::size_t CachedFusion::batch() const { return std::size_t(std::max(1, kSensorsPerCycle / shape_.sources)); }

CachedFusion::Graph& CachedFusion::graph_for(std::size_t k) {
    auto it = std::find_if(graphs_.begin(), graphs_.end(), [&](const Graph& g) { return g.k == k; });
    if (it != graphs_.end()) {
        graphs_.splice(graphs_.end(), graphs_, it);
        return graphs_.back();
    }
    if (graphs_.size() == kGraphsKept) graphs_.pop_front();
    // Recorded aside and kept only once whole: a recording that throws
    // (out of memory) leaves no half-recorded cycle behind.
    std::list<Graph> fresh;
    Graph& gr = fresh.emplace_back();
    gr.k = k;
    gr.cfg = base_config(shape_);
    gr.cfg.sensors = int(batch()) * shape_.sources;
    gr.cfg.frames = int(k);
    gr.table = Buffer(ctx_, std::uint64_t(gr.cfg.sensors) * k * 4, MemoryUse::Upload);
    gr.readback = Buffer(ctx_, std::uint64_t(gr.cfg.sensors) * metric_groups(gr.cfg) * kMetricPartialFloats * 4,
                         MemoryUse::Readback);
    gr.sets.emplace(ctx_);
    gr.slot.emplace(ctx_, 0);
    Recorder rec(ctx_, gr.slot->recording_target(), gr.slot->queries(), "", *gr.sets, addressed_);
    std::vector<DeviceSpan> fixed{gr.table.span(), gr.readback.span()};
    for (const Buffer& b : cache_->buffers) fixed.push_back(b.span());
    GraphBuilder g{ctx_, gr.cfg, rec, gr.buffers, 0, fixed};
    const std::uint32_t sources = std::uint32_t(shape_.sources);
    const VkDeviceAddress fused =
        method_recorder(shape_.fusion.method).fuse_cached(g, cache_->groups, sources, gr.table.span());
    record_metrics(g, fused, fused, gr.readback.span(), std::nullopt, std::uint32_t(shape_.sources));
    rec.finish();
    graphs_.splice(graphs_.end(), fresh);
    return graphs_.back();
}

std::vector<std::vector<Metrics>> CachedFusion::score(std::span<const std::vector<std::size_t>> combinations) {
    std::vector<std::vector<Metrics>> out;
    if (combinations.empty()) return out;
    const std::size_t k = combinations.front().size();
    for (const auto& c : combinations) {
        if (c.size() != k || k < 2)
            throw Error(ErrorKind::InvalidArgument, "cached fusion: combinations of one size, two frames or more");
        for (std::size_t i = 0; i < k; ++i)
            if (c[i] >= std::size_t(shape_.frames) || std::count(c.begin(), c.end(), c[i]) != 1)
                throw Error(ErrorKind::InvalidArgument, "cached fusion: a combination names a frame twice or past " +
                                                            std::to_string(shape_.frames));
    }
    Graph& gr = graph_for(k);
    const std::size_t S = std::size_t(shape_.sources), full = batch(), group_size = cache_->groups.front().count;
    const std::size_t n_floats = metric_groups(gr.cfg) * kMetricPartialFloats;
    for (std::size_t first = 0; first < combinations.size(); first += full) {
        const std::size_t count = std::min(full, combinations.size() - first);
        // A short last batch repeats its last combination in the slots left.
        auto* table = static_cast<std::uint32_t*>(gr.table.mapped());
        for (std::size_t b = 0; b < full; ++b) {
            const auto& c = combinations[first + std::min(b, count - 1)];
            for (std::size_t s = 0; s < S; ++s)
                for (std::size_t i = 0; i < k; ++i)
                    table[(b * S + s) * k + i] =  // frame c[i] of source s among its group's
                        std::uint32_t(s % group_size * std::size_t(shape_.frames) + c[i]);
        }
        gr.slot->submit_and_wait();
        gr.readback.invalidate();
        const float* partials = static_cast<const float*>(gr.readback.mapped());
        for (std::size_t b = 0; b < count; ++b) {
            std::vector<Metrics> row;
            for (std::size_t s = 1; s < S; ++s) {
                const std::span<const float> p(partials + (b * S + s) * n_floats, n_floats);
                row.push_back(finish_metrics(p, gr.cfg, 0, "cached fusion: source " + std::to_string(s)));
            }
            out.push_back(std::move(row));
        }
    }
    return out;
}

}  // namespace vkfuse::vk

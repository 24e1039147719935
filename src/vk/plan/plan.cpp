#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>

#include "core/validate_shape.hpp"
#include "vk/engine/magnitude.hpp"
#include "vk/plan/method_recorders.hpp"
#include "vk/plan/sensor_blocks.hpp"
#include "vk/plan/plan_impl.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace {

void validate_config(const PlanConfig& c, vk::PlanKind kind) {
    if (kind == vk::PlanKind::Fuse) {
        validate(c.fusion, c.height, c.width, c.channels, c.frames);
    } else {
        core::validate_shape(c.height, c.width, c.channels, c.frames);
        if (kind == vk::PlanKind::Score && c.frames != 1)
            throw Error(ErrorKind::InvalidArgument, "plan: an unfused plan (fuse = false) scores 1 frame per sensor, got " +
                                                        std::to_string(c.frames));
    }
    if (c.sensors < 1) throw Error(ErrorKind::InvalidArgument, "plan: sensors must be >= 1");
    if (c.cycles_in_flight != 1 && c.cycles_in_flight != 2)
        throw Error(ErrorKind::InvalidArgument, "plan: cycles_in_flight must be 1 or 2, got " +
                                                    std::to_string(c.cycles_in_flight));
    if (c.cycles_in_flight != 1 && c.skip.policy != SkipPolicy::Off)
        throw Error(ErrorKind::InvalidArgument, "plan: a skipping plan keeps its references and held results "
                                                "once, so it keeps 1 cycle in flight, not " +
                                                    std::to_string(c.cycles_in_flight));
    if (c.skip.policy != SkipPolicy::Off) {
        if (kind != vk::PlanKind::Fuse || c.input != PixelType::U8)
            throw Error(ErrorKind::InvalidArgument, "plan: skip " + std::string(to_string(c.skip.policy)) +
                                                        " needs a fusing plan of 8-bit frames");
        if (!(c.skip.threshold > 0) || !std::isfinite(c.skip.threshold))
            throw Error(ErrorKind::InvalidArgument, "plan: skip threshold must be a finite number > 0");
    }
    // Kernels index with 32-bit integers: keep every buffer below 2^32 floats.
    const double elems = double(c.height) * c.width * c.channels * c.frames * c.sensors;
    if (elems * 2 >= double(std::numeric_limits<std::uint32_t>::max()))
        throw Error(ErrorKind::InvalidArgument, "plan: " + std::to_string(c.sensors) + " sensors x " +
                                                    std::to_string(c.frames) + " frames of " + std::to_string(c.width) +
                                                    "x" + std::to_string(c.height) + " exceed one plan's size limit");
}

std::size_t pixel_bytes(PixelType t) { return t == PixelType::U8 ? 1 : 4; }

// One of the plan's buffers that hold a slice per sensor, whole (a null span
// where the plan has none of it), and the bytes of each sensor's slice.
struct PerSensor {
    vk::DeviceSpan all;
    std::uint64_t stride;
};
// The frames as uploaded (or the caller's), the read-back image (or the
// caller's), the metric partials, the backgrounds and Brovey's thresholds.
struct PerSensorBuffers {
    PerSensor frames, image, partials, backgrounds, thresholds;
    std::array<PerSensor, 5> each() const { return {frames, image, partials, backgrounds, thresholds}; }
};
PerSensorBuffers per_sensor_buffers(const Plan::Impl& p) {
    const PlanConfig& c = p.cfg;
    const std::uint64_t samples = std::uint64_t(c.height) * std::uint64_t(c.width) * std::uint64_t(c.channels);
    const vk::DeviceSpan image = !c.want_fused             ? vk::DeviceSpan{}
                                 : p.device_fused.handle() ? p.device_fused.span()
                                                           : p.readback.span().sub(0, p.partials_offset);
    const vk::DeviceSpan frames = p.staged_frames.handle()   ? p.staged_frames.span()
                                  : p.device_frames.handle() ? p.device_frames.span()
                                                             : p.upload.span();
    return {{frames,
             samples * pixel_bytes(c.input) * std::uint64_t(c.frames)},
            {image, samples * 4},
            {c.metrics.empty() ? vk::DeviceSpan{} : p.readback.span().sub(p.partials_offset),
             std::uint64_t(vk::metric_groups(c)) * vk::kMetricPartialFloats * 4},
            {p.background.span(), samples * 4},
            {p.thresholds.span(), 4}};
}

void check_precision(const PlanConfig& c, const DeviceInfo& device) {
    if (c.precision == Precision::Fp16Storage && !device.fp16_storage)
        throw Error(ErrorKind::Device, "precision fp16: " + device.name +
                                           " lacks 16-bit storage buffers or float16 shaders");
}

// The kernels of one precision: shaders/<name>.comp built with float16 planes
// is embedded as <name>_fp16 (CMakeLists.txt).
std::string kernel_variant(Precision p) { return p == Precision::Fp16Storage ? "_fp16" : ""; }

}  // namespace

std::string_view to_string(Precision p) { return p == Precision::Fp16Storage ? "fp16" : "fp32"; }

Plan::Impl::Impl(Context::Impl& context, const PlanConfig& config, vk::PlanKind plan_kind, const PlanBuffers* io)
    : ctx(context), cfg(config), kind(plan_kind), embedded(io != nullptr) {
    validate_config(cfg, kind);
    check_precision(cfg, ctx.info);
    if (io && cfg.cycles_in_flight != 1)
        throw Error(ErrorKind::InvalidArgument, "make_plan: a plan in the caller's command buffers keeps 1 cycle "
                                                "in flight (the caller pipelines its own submissions)");
    if (io) borrow_buffers(*io);
    const std::size_t frame_bytes = std::size_t(cfg.height) * cfg.width * cfg.channels * pixel_bytes(cfg.input);
    const std::size_t plane_floats = std::size_t(cfg.height) * cfg.width;
    const std::size_t sensor_floats = plane_floats * cfg.channels;
    if (!device_frames.handle())
        upload = vk::Buffer(ctx, (frame_bytes * cfg.frames * cfg.sensors + 3) / 4 * 4, vk::MemoryUse::Upload);
    if (upload.handle() && !upload.device_local() && ctx.memory_types.has_device_local()) {
        staged_frames = vk::Buffer(ctx, upload.size(), vk::MemoryUse::Device);
        ctx.adapted("frames uploaded to system memory are copied into device-local memory before each cycle");
    }
    if (device_frames.handle() && ctx.in_system_memory(device_frames.handle())) {
        staged_frames = vk::Buffer(ctx, (device_frames.size() + 3) / 4 * 4, vk::MemoryUse::Device);
        ctx.adapted("frames in imported host memory are copied into device-local memory before each cycle");
    }
    // A skipping plan that decides on the device fills its slots' backgrounds there.
    if (cfg.metrics.has(Metric::BackgroundDiff))
        background = vk::Buffer(ctx, sensor_floats * cfg.sensors * 4,
                                vk::skip_decides_on_device(cfg) ? vk::MemoryUse::Device : vk::MemoryUse::Upload);
    const std::size_t S = std::size_t(cfg.sensors);
    if (cfg.input == PixelType::F32 && brovey()) {
        thresholds = vk::Buffer(ctx, S * 4, vk::MemoryUse::Upload);
        std::fill_n(static_cast<float*>(thresholds.mapped()), S, vk::brovey_threshold(0));
    }
    exponent.assign(S, 0);
    next_exponent.assign(S, 0);
    if (cfg.metrics.has(Metric::BackgroundDiff) && (cfg.input == PixelType::F32 || cfg.skip.policy != SkipPolicy::Off)) {
        background_host.resize(sensor_floats * S);
        background_max.assign(S, 0);
        background_exponent.assign(S, std::nullopt);
    }
    const std::size_t fused_bytes = cfg.want_fused && !device_fused.handle() ? sensor_floats * cfg.sensors * 4 : 0;
    // Partials start on a boundary any device accepts as a binding offset.
    partials_offset = (fused_bytes + 255) / 256 * 256;
    const std::size_t partial_bytes =
        !cfg.metrics.empty() ? S * vk::metric_groups(cfg) * vk::kMetricPartialFloats * sizeof(float) : 16;
    readback = vk::Buffer(ctx, partials_offset + partial_bytes, vk::MemoryUse::Readback);
    if (cfg.profile && !ctx.timestamps())
        throw Error(ErrorKind::Device, ctx.info.name + ": no timestamp queries for --profile");
    // Should anything here throw, the members built so far release themselves.
    // Room for every block's stages (vk/plan/sensor_blocks.hpp).
    slot.emplace(ctx, cfg.profile ? vk::Recorder::kMaxTimestamps * blocks() : 0, embedded);
    record();
    if (embedded) slot->record_primary();
    background_set.assign(std::size_t(cfg.sensors), false);
    fused.resize(std::size_t(cfg.sensors));
    fused_fresh.assign(std::size_t(cfg.sensors), false);
}

std::uint32_t Plan::Impl::sensors_per_block() const {
    const auto S = std::uint32_t(cfg.sensors);
    const auto& limits = ctx.properties.limits;
    if (ctx.device_addresses_only) return 0;
    // A skipping plan compacts its fused sensors into the first slots of
    // every buffer, and its change detection binds per-sensor means beside
    // them (what largest_buffer_bytes bounds): one block, bound or addressed.
    if (cfg.skip.policy != SkipPolicy::Off) return vk::needs_device_addresses(cfg, limits) ? 0 : S;
    std::vector<std::uint64_t> strides;  // of the per-sensor buffers the plan has
    for (const PerSensor& b : per_sensor_buffers(*this).each())
        if (b.all.buffer) strides.push_back(b.stride);
    PlanConfig one = cfg;
    one.sensors = 1;
    return vk::sensors_per_binding(S, vk::plan_buffer_bytes(one, kind), strides, limits.maxStorageBufferRange,
                                   limits.minStorageBufferOffsetAlignment);
}

std::uint32_t Plan::Impl::blocks() const {
    const std::uint32_t block = sensors_per_block();
    return block == 0 ? 1 : (std::uint32_t(cfg.sensors) + block - 1) / block;
}

void Plan::Impl::record() {
    // Sensors per recorded block (vk/plan/sensor_blocks.hpp); 0: every sensor in
    // one block through device addresses.
    const auto S = std::uint32_t(cfg.sensors);
    std::uint32_t block = sensors_per_block();
    addressed = block == 0;
    if (addressed) block = S;
    sets.emplace(ctx);
    vk::Recorder rec(ctx, slot->recording_target(), slot->queries(), kernel_variant(cfg.precision), *sets, addressed,
                     embedded, slot->query_count());
    if (staged_frames.handle()) {
        // From the upload buffer (host-written), or from the caller's frames
        // in imported host memory (host-written, or by the caller's commands).
        const VkCommandBuffer cmd = slot->recording_target();
        const vk::DeviceSpan from = device_frames.handle() ? device_frames.span() : upload.span();
        vk::memory_barrier(*ctx.api, cmd, VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                           VK_ACCESS_HOST_WRITE_BIT | VK_ACCESS_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_READ_BIT);
        const VkBufferCopy all{from.offset, 0, from.bytes};
        ctx.api->vkCmdCopyBuffer(cmd, from.buffer, staged_frames.handle(), 1, &all);
        vk::memory_barrier(*ctx.api, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    }
    if (cfg.skip.policy != SkipPolicy::Off) {
        skip.emplace(ctx, cfg, upload, addressed);
        if (skip->on_device())
            skip->record_on_device(rec, slot->recording_target(), per_sensor_buffers(*this).frames.all, background.span());
        rec.compact_sensors(skip->indirect(), vk::SkipState::kFusionDispatches, S);
        background_in_slot.assign(std::size_t(cfg.sensors), -1);
    }
    const std::size_t first_intermediate = buffers.size();
    for (std::uint32_t from = 0; from < S; from += block)
        record_sensors(rec, from, std::min(block, S - from),
                       from == 0 ? std::nullopt : std::optional<std::size_t>(first_intermediate));
    rec.finish();
    dispatches = rec.dispatches();
    barriers = rec.barriers();
    stage_names = rec.stage_names();
    if (skip) skip->set_dispatches(rec.sensor_dispatches());
}

void Plan::Impl::record_sensors(vk::Recorder& rec, std::uint32_t from, std::uint32_t count,
                                std::optional<std::size_t> reuse_from) {
    PlanConfig block = cfg;
    block.sensors = int(count);
    // This block's range of a per-sensor buffer (the whole of it for one
    // block; the last block's runs to the end of its buffer).
    const bool whole = count == std::uint32_t(cfg.sensors), last = from + count == std::uint32_t(cfg.sensors);
    auto range = [&](const PerSensor& b) {
        return !b.all.buffer || whole ? b.all : b.all.sub(from * b.stride, last ? 0 : count * b.stride);
    };
    const PerSensorBuffers per = per_sensor_buffers(*this);
    const vk::DeviceSpan frames = range(per.frames), image = range(per.image), partials = range(per.partials),
                         backgrounds = range(per.backgrounds), block_thresholds = range(per.thresholds);
    vk::GraphBuilder g{ctx, block, rec, buffers, block_thresholds.buffer ? block_thresholds.address() : 0,
                       {frames, image, partials, backgrounds, block_thresholds}};
    g.reuse_from = reuse_from;
    if (skip) g.sparse = skip->sparse();
    const std::uint32_t pixels = std::uint32_t(cfg.width) * std::uint32_t(cfg.height);
    const bool quads = pixels % 4 == 0;  // the kernels' four-pixel paths
    const std::optional<vk::DeviceSpan> wanted_image = cfg.want_fused ? std::optional(image) : std::nullopt;
    VkDeviceAddress fused_planes = 0;
    bool pointwise = false;  // the fusion kernel wrote the image itself
    vk::FrameSource input(g, frames);
    switch (kind) {
        case vk::PlanKind::Fuse: {
            const vk::MethodRecorder& method = vk::method_recorder(cfg.fusion.method);
            pointwise = method.shape == vk::GraphShape::Pointwise;
            fused_planes = method.record(g, input, wanted_image, method.pointwise_kernel);
            break;
        }
        case vk::PlanKind::Score: fused_planes = input.planes(); break;  // the frame is its own result
        case vk::PlanKind::BackgroundMean:
            pointwise = true;
            fused_planes = record_pointwise(g, frames, wanted_image, vk::kPointwiseMean, "mean");
            break;
    }
    if (!pointwise) {
        if (cfg.want_fused && !vk::metrics_write_image(cfg)) {
            const vk::DeviceSpan fused = g.span(fused_planes);
            rec.dispatch("pack", {fused, fused, image, image},
                         vk::PushConstants()
                             .u32("pixels", pixels)
                             .u32("channels", std::uint32_t(cfg.channels))
                             .u32("quads", quads),
                         vk::Recorder::LinearWork{quads ? pixels / 4 : pixels, count});
            rec.mark("pack");
        }
    }
    const bool packs = cfg.want_fused && !pointwise && vk::metrics_write_image(cfg);
    if (!cfg.metrics.empty())
        record_metrics(g, fused_planes, background.handle() ? backgrounds.address() : 0, partials,
                       packs ? std::optional(image) : std::nullopt);
}

void Plan::Impl::wait_device() {
    if (!submitted) return;
    slot->wait();
    submitted = false;
}

namespace {

void check_view(const FrameView& v, const PlanConfig& c, const std::string& what, bool any_type = false) {
    if (!v.data) throw Error(ErrorKind::InvalidArgument, what + ": no pixel data");
    if (v.height != c.height || v.width != c.width || v.channels != c.channels)
        throw Error(ErrorKind::Shape, what + ": shape " + std::to_string(v.height) + "x" + std::to_string(v.width) + "x" +
                                          std::to_string(v.channels) + " differs from the plan's " +
                                          std::to_string(c.height) + "x" + std::to_string(c.width) + "x" +
                                          std::to_string(c.channels));
    if (!any_type && v.type != c.input) throw Error(ErrorKind::InvalidArgument, what + ": pixel type differs from the plan's");
}

// "row 3, column 5, channel 2" for sample i of an HWC image of the plan's shape.
std::string position(const PlanConfig& c, std::size_t i) {
    const std::size_t C = std::size_t(c.channels), pixel = i / C;
    return "row " + std::to_string(pixel / std::size_t(c.width)) + ", column " +
           std::to_string(pixel % std::size_t(c.width)) + ", channel " + std::to_string(i % C);
}

// "NaN at row 3, column 5, channel 2", as the reference words bad input.
std::string non_finite_at(const PlanConfig& c, float v, std::size_t i) {
    return std::string(std::isnan(v) ? "NaN" : v > 0 ? "Inf" : "-Inf") + " at " + position(c, i);
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

}  // namespace

Plan::Plan(Context& context, const PlanConfig& config)
    : impl_(Impl::with_lanes(vk::ContextAccess::of(context), config,
                             config.fuse ? vk::PlanKind::Fuse : vk::PlanKind::Score)) {}
Plan::Plan(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
namespace vk {
Plan make_plan_of_kind(Context& context, const PlanConfig& config, PlanKind kind) {
    return Plan::Impl::make(context, config, kind);
}
}  // namespace vk

Plan Plan::Impl::make(Context& context, const PlanConfig& config, vk::PlanKind plan_kind) {
    return Plan(with_lanes(vk::ContextAccess::of(context), config, plan_kind));
}
std::unique_ptr<Plan::Impl> Plan::Impl::with_lanes(Context::Impl& context, const PlanConfig& config,
                                                   vk::PlanKind plan_kind) {
    auto first = std::make_unique<Impl>(context, config, plan_kind);
    if (config.cycles_in_flight == 2) first->second_lane = std::make_unique<Impl>(context, config, plan_kind);
    return first;
}
Plan::~Plan() = default;
Plan::Plan(Plan&&) noexcept = default;
Plan& Plan::operator=(Plan&&) noexcept = default;
const PlanConfig& Plan::config() const { return impl_->cfg; }

void Plan::set_background(int sensor, const FrameView& bg) {
    auto& p = *impl_;
    if (!p.cfg.metrics.has(Metric::BackgroundDiff))
        throw Error(ErrorKind::InvalidArgument, "plan: created without the background_diff metric");
    if (sensor < 0 || sensor >= p.cfg.sensors)
        throw Error(ErrorKind::InvalidArgument, "background: sensor " + std::to_string(sensor) + " out of range");
    check_view(bg, p.cfg, "background of sensor " + std::to_string(sensor), true);
    p.finish_pending();  // a submitted cycle may still read the device copy
    // Cycles in flight were submitted with the old background: each lane's
    // device copy changes once its cycle is done (it stays to be collected).
    for (Impl* lane : p.lanes()) {
        lane->wait_device();
        lane->set_background(sensor, bg);
    }
}

void Plan::Impl::set_background(int sensor, const FrameView& bg) {
    auto& im = *this;
    const std::string name = "background of sensor " + std::to_string(sensor);
    const std::size_t pixels = std::size_t(bg.height) * bg.width, C = std::size_t(bg.channels);
    if (bg.type == PixelType::F32) {
        const std::uint32_t largest = vk::max_abs(bg.data, pixels * C);
        if (largest >= vk::kNonFinite) {
            const std::size_t i = vk::first_non_finite(bg.data, pixels * C);
            throw Error(ErrorKind::Numeric, name + ": " + non_finite_at(im.cfg, vk::load(bg.data, i), i));
        }
        // Frames of 8 bits are never scaled (vk/engine/magnitude.hpp): a background
        // this small would lose its significant bits to the subnormal
        // flushing of the device where a frame is black.
        if (im.cfg.input == PixelType::U8 && largest != 0 && std::bit_cast<float>(largest) < 0x1p-64f)
            throw Error(ErrorKind::Numeric, name + ": largest magnitude " + number(std::bit_cast<float>(largest)) +
                                                " is below 2^-64, too small to compare with 8-bit frames on the "
                                                "device; give the plan float32 frames");
    }
    // Backgrounds change rarely: convert to planar float here, once, on the
    // host. A float32 plan keeps them here and writes the device copy at each
    // run's scale.
    const bool scaled = !im.background_host.empty();
    float* dst = (scaled ? im.background_host.data() : static_cast<float*>(im.background.mapped())) +
                 std::size_t(sensor) * pixels * C;
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < C; ++c)
            dst[c * pixels + p] = bg.type == PixelType::U8
                                      ? float(static_cast<const std::uint8_t*>(bg.data)[p * C + c]) / 255.0f
                                      : static_cast<const float*>(bg.data)[p * C + c];
    if (scaled) {
        im.background_max[std::size_t(sensor)] = vk::max_abs(dst, pixels * C);
        im.background_exponent[std::size_t(sensor)] = std::nullopt;
    }
    im.background_set[std::size_t(sensor)] = true;
    if (im.skip) {
        im.skip->background_changed(sensor);
        im.skip->set_background(sensor, dst);
        for (int& held : im.background_in_slot)
            if (held == sensor) held = -1;
    }
}

void Plan::set_skip_reference(int sensor, const SkipReference& reference) {
    auto& im = *impl_;  // a skipping plan has one lane
    if (!im.skip) throw Error(ErrorKind::InvalidArgument, "plan: created with skip off");
    if (sensor < 0 || sensor >= im.cfg.sensors)
        throw Error(ErrorKind::InvalidArgument, "skip reference: sensor " + std::to_string(sensor) + " out of range");
    im.skip->set_reference(sensor, reference);
}

SkipOutcome Plan::skip_outcome(int sensor) const {
    auto& im = *impl_;
    if (sensor < 0 || sensor >= im.cfg.sensors)
        throw Error(ErrorKind::InvalidArgument, "plan: sensor " + std::to_string(sensor) + " out of range");
    if (!im.skip) return {};
    return im.readable("skip_outcome()").skip->outcome(sensor);
}

namespace {

// Float32 frames into the upload buffer, sensor by sensor: copied while their
// largest magnitude is found, and where that lies outside the ordinary band,
// copied again times 2^-e (vk/engine/magnitude.hpp). The scales, Brovey's thresholds
// and the backgrounds' device copies change only once every sensor passed, so
// a run that throws here leaves the last run's results readable.
void upload_f32(Plan::Impl& im, std::span<const FrameView> frames) {
    const PlanConfig& c = im.cfg;
    const std::size_t S = std::size_t(c.sensors), K = std::size_t(c.frames);
    const std::size_t n = std::size_t(c.height) * c.width * c.channels;
    float* upload = static_cast<float*>(im.upload.mapped());
    for (std::size_t s = 0; s < S; ++s) {
        float* dst = upload + s * K * n;
        std::uint32_t largest = 0;
        for (std::size_t k = 0; k < K; ++k)
            largest = std::max(largest, vk::copy_magnitude(dst + k * n, frames[s * K + k].data, n));
        if (largest == 0)  // black, or nothing but the smallest subnormals
            for (std::size_t k = 0; k < K; ++k) largest = std::max(largest, vk::max_abs(frames[s * K + k].data, n));
        if (largest >= vk::kNonFinite)
            for (std::size_t k = 0; k < K; ++k) {
                const std::size_t i = vk::first_non_finite(frames[s * K + k].data, n);
                if (i < n)
                    throw Error(ErrorKind::Numeric, "frame " + std::to_string(k) + " of sensor " + std::to_string(s) +
                                                        ": " + non_finite_at(c, vk::load(frames[s * K + k].data, i), i));
            }
        const std::uint32_t background = im.background_max.empty() ? 0 : im.background_max[s];
        const std::optional<int> e = vk::choose_exponent(largest, background, im.brovey(), im.ctx.info.float32_subnormals);
        if (!e) {
            std::uint32_t exact = 0;
            for (std::size_t k = 0; k < K; ++k) exact = std::max(exact, vk::max_abs(frames[s * K + k].data, n));
            throw Error(ErrorKind::Numeric, "sensor " + std::to_string(s) + ": frames of largest magnitude " +
                                                number(std::bit_cast<float>(exact)) + " and a background of " +
                                                number(std::bit_cast<float>(background)) +
                                                " lie too far apart to share one float32 scale on the device");
        }
        // The host scales results back on the way out; an image written into
        // a caller's buffer never passes it, so it would stay scaled.
        if (*e != 0 && im.device_fused.handle())
            throw Error(ErrorKind::Numeric, "sensor " + std::to_string(s) + ": frames of largest magnitude " +
                                                number(std::bit_cast<float>(largest)) +
                                                " need scaling on the device, which the fused image written to the "
                                                "caller's buffer (PlanBuffers::fused) would keep; give frames within "
                                                "[2^-40, 2^40)");
        if (*e != 0)
            for (std::size_t k = 0; k < K; ++k) vk::copy_scaled(dst + k * n, frames[s * K + k].data, n, *e);
        im.next_exponent[s] = *e;
    }
    for (std::size_t s = 0; s < S; ++s) {
        const int e = im.next_exponent[s];
        im.exponent[s] = e;
        if (im.thresholds.mapped()) static_cast<float*>(im.thresholds.mapped())[s] = vk::brovey_threshold(e);
        if (!im.background_host.empty() && im.background_exponent[s] != e) {
            vk::copy_scaled(static_cast<float*>(im.background.mapped()) + s * n, im.background_host.data() + s * n, n, e);
            im.background_exponent[s] = e;
        }
    }
}

}  // namespace

void Plan::Impl::check_ready() const {
    if (cfg.metrics.has(Metric::BackgroundDiff))
        for (int s = 0; s < cfg.sensors; ++s)
            if (!background_set[std::size_t(s)])
                throw Error(ErrorKind::InvalidArgument, "plan run: no background set for sensor " + std::to_string(s));
    if (skip)
        for (int s = 0; s < cfg.sensors; ++s)
            if (!skip->has_reference(s))
                throw Error(ErrorKind::InvalidArgument, "plan run: no skip reference set for sensor " + std::to_string(s));
}

void Plan::Impl::upload_frames(std::span<const FrameView> frames) {
    auto& im = *this;
    const auto& c = cfg;
    if (device_frames.handle())
        throw Error(ErrorKind::InvalidArgument, "plan run: this plan reads its frames from a device buffer "
                                                "(PlanBuffers::frames); give it none");
    const std::size_t expected = std::size_t(c.sensors) * c.frames;
    if (frames.size() != expected)
        throw Error(ErrorKind::InvalidArgument, "plan run: got " + std::to_string(frames.size()) + " frames, expected " +
                                                    std::to_string(c.sensors) + " sensors x " +
                                                    std::to_string(c.frames) + " = " + std::to_string(expected));
    for (std::size_t i = 0; i < frames.size(); ++i)
        check_view(frames[i], c, "frame " + std::to_string(i % c.frames) + " of sensor " + std::to_string(i / c.frames));
    check_ready();
    if (c.input == PixelType::F32) {
        upload_f32(im, frames);
    } else {  // 8-bit frames, in [0, 1] on the device: as they are
        auto* dst = static_cast<std::uint8_t*>(im.upload.mapped());
        for (const auto& f : frames) {
            std::memcpy(dst, f.data, f.bytes());
            dst += f.bytes();
        }
    }
}

void Plan::Impl::prepare_device_frames() {
    const std::size_t n = std::size_t(cfg.height) * cfg.width * cfg.channels;
    for (std::size_t s = 0; s < std::size_t(cfg.sensors); ++s) {
        exponent[s] = 0;
        if (!background_host.empty() && background_exponent[s] != 0) {
            vk::copy_scaled(static_cast<float*>(background.mapped()) + s * n, background_host.data() + s * n, n, 0);
            background_exponent[s] = 0;
        }
    }
}

void Plan::Impl::complete() {
    readback.invalidate();  // what the cycle wrote, visible where read-back memory is not coherent
    // Decided on the device: whether it fused anyone is known now. A cycle
    // that fused no one counts no fusion submit (Plan::submits).
    if (skip && skip->on_device()) {
        fused_last_run = skip->read_decision() > 0;
        submits += fused_last_run;
    }
    collected = true;
    std::fill(fused_fresh.begin(), fused_fresh.end(), false);
}

Plan::Impl& Plan::Impl::readable(const char* call) const {
    if (!collected) {
        throw Error(ErrorKind::InvalidArgument, std::string("plan: ") + call +
                                                    (in_flight.empty() ? " before run()"
                                                                       : " after submit(); collect() its cycle first"));
    }
    check_not_pending(call);
    return *results;
}

void Plan::Impl::check_not_pending(const char* call) const {
    if (pending)
        throw Error(ErrorKind::InvalidArgument, std::string("plan: ") + call +
                                                    " while a submitted cycle is pending; vkfuse::wait(plan) first");
}

void Plan::Impl::finish_pending() {
    if (!pending) return;
    pending = false;
    slot->wait();
    complete();
}

const Image& Plan::fused(int sensor) const {
    if (!impl_->cfg.want_fused) throw Error(ErrorKind::InvalidArgument, "plan: created without want_fused");
    if (impl_->device_fused.handle())
        throw Error(ErrorKind::InvalidArgument, "plan: the fused image is written to the caller's buffer "
                                                "(PlanBuffers::fused), not read back");
    // The cache of images read back is the lane's own.
    Impl& im = impl_->readable("fused()");
    if (sensor < 0 || sensor >= im.cfg.sensors)
        throw Error(ErrorKind::InvalidArgument, "plan: sensor " + std::to_string(sensor) + " out of range");
    if (im.skipped(sensor)) return im.skip->skipped_image(sensor);
    auto& img = im.fused[std::size_t(sensor)];
    if (!im.fused_fresh[std::size_t(sensor)]) {
        // The last cycle's image is written over in place: no allocation and
        // no zero fill of a buffer every sample of which is written next.
        if (img.height != im.cfg.height || img.width != im.cfg.width || img.channels != im.cfg.channels)
            img = Image(im.cfg.height, im.cfg.width, im.cfg.channels);
        Image& out = img;
        const float* src = static_cast<const float*>(im.readback.mapped()) + im.result_slot(sensor) * out.size();
        const int e = im.exponent[std::size_t(sensor)];
        if (e == 0) {  // copied and checked in one pass
            if (vk::copy_magnitude(out.data.data(), src, out.size()) >= vk::kNonFinite)
                vk::check_device_results(im.cfg, "sensor " + std::to_string(sensor), std::span(src, out.size()), "the fused image");
        } else {  // back to the frames' scale: exact, unless it leaves float32's range
            vk::check_device_results(im.cfg, "sensor " + std::to_string(sensor), std::span(src, out.size()), "the fused image");
            const std::size_t i = vk::scale_back(out.data.data(), src, out.size(), e);
            if (i < out.size())
                throw Error(ErrorKind::Numeric, "sensor " + std::to_string(sensor) + ": fused value " +
                                                    number(std::ldexp(double(src[i]), e)) + " at " +
                                                    position(im.cfg, i) + " lies beyond float32's range");
        }
        im.fused_fresh[std::size_t(sensor)] = true;
    }
    return img;
}

Metrics Plan::metrics(int sensor) const {
    if (impl_->cfg.metrics.empty()) throw Error(ErrorKind::InvalidArgument, "plan: created without metrics");
    Impl& im = impl_->readable("metrics()");
    if (sensor < 0 || sensor >= im.cfg.sensors)
        throw Error(ErrorKind::InvalidArgument, "plan: sensor " + std::to_string(sensor) + " out of range");
    if (im.skipped(sensor)) {
        const std::size_t n = std::size_t(im.cfg.height) * im.cfg.width * im.cfg.channels;
        return im.skip->skipped_metrics(
            sensor, im.cfg.metrics.has(Metric::BackgroundDiff) ? im.background_host.data() + std::size_t(sensor) * n : nullptr);
    }
    const std::size_t groups = vk::metric_groups(im.cfg), n_floats = groups * vk::kMetricPartialFloats;
    const float* partials = reinterpret_cast<const float*>(static_cast<const std::uint8_t*>(im.readback.mapped()) +
                                                           im.partials_offset) +
                            im.result_slot(sensor) * n_floats;
    return vk::finish_metrics(std::span(partials, n_floats), im.cfg, im.exponent[std::size_t(sensor)],
                              "sensor " + std::to_string(sensor));
}

std::uint64_t Plan::submits() const {
    return impl_->submits + (impl_->second_lane ? impl_->second_lane->submits : 0);
}

std::vector<KernelTime> Plan::profile() const {
    if (!impl_->cfg.profile) throw Error(ErrorKind::InvalidArgument, "plan: created without profile");
    if (!impl_->collected) return {};
    Impl& im = impl_->readable("profile()");
    if (!im.fused_last_run) return {};
    const std::uint32_t n = std::uint32_t(im.stage_names.size()) + 1;
    const std::vector<std::uint64_t> ticks = im.slot->timestamps(n);
    std::vector<KernelTime> out;
    const double ns_per_tick = im.ctx.properties.limits.timestampPeriod;
    // A plan recorded in blocks of sensors (vk/plan/sensor_blocks.hpp) runs each
    // stage once per block: a stage's time is the sum over its blocks.
    for (std::uint32_t i = 0; i + 1 < n; ++i) {
        const double ms = double(ticks[i + 1] - ticks[i]) * ns_per_tick * 1e-6;
        auto same = std::find_if(out.begin(), out.end(), [&](const KernelTime& k) { return k.name == im.stage_names[i]; });
        if (same != out.end())
            same->ms += ms;
        else
            out.push_back({im.stage_names[i], ms});
    }
    return out;
}

}  // namespace vkfuse

// The pass graph's building blocks: what a graph builder records a plan's
// passes with (GraphBuilder, FrameSource, PlaneView, SensorGroup) and the
// record_* passes the method rows and the study's cache put together. The
// plan itself (Plan::Impl, vk/plan/plan_impl.hpp) is built on these; nothing here
// sees it.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "vk/engine/buffer.hpp"
#include "vk/engine/kernel_codes.hpp"
#include "vk/engine/recorder.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::vk {

class SparseRegions;  // vk/passes/plan_sparse.hpp

// What a plan computes for each sensor. Only Fuse runs a fusion method
// (PlanConfig::fusion); the others are kinds of plan of their own.
enum class PlanKind {
    Fuse,            // the K frames fused, then the metrics of the result
    Score,           // the one frame as it is, and its metrics (PlanConfig::fuse false)
    BackgroundMean,  // the per-pixel mean of the K frames (BackgroundModel)
};

// A plan of that kind, for the library's modules that need one of their own
// (the rig's background model) without the plan's internals.
Plan make_plan_of_kind(Context& context, const PlanConfig& config, PlanKind kind);

// What a graph builder works with while a plan is being recorded.
struct GraphBuilder {
    Context::Impl& ctx;
    const PlanConfig& cfg;
    Recorder& rec;
    std::vector<Buffer>& buffers;  // owned by the plan; every intermediate lives here
    // Brovey in a float32-input plan: per sensor, the dark threshold in that
    // sensor's scaled domain (vk/engine/magnitude.hpp), host-written every run; 0
    // otherwise (8-bit frames are never scaled: the kernel's own 1e-6).
    VkDeviceAddress brovey_thresholds = 0;
    // The ranges of the plan's buffers outside `buffers` (upload, background,
    // readback) that this recording reaches: whole, or one block's sensors.
    std::vector<DeviceSpan> fixed;
    // Tile-sparse fusion (vk/passes/plan_sparse.hpp): the region records the
    // wavelet's dispatches declare theirs in; null when the plan fuses whole.
    SparseRegions* sparse = nullptr;
    // A later block of a plan's sensors (SensorBlocks): the intermediates are
    // the first block's, taken again in the order it made them, from this
    // index of `buffers` on. nullopt: every intermediate is a new buffer.
    std::optional<std::size_t> reuse_from = std::nullopt;

    std::uint32_t planes_in() const { return std::uint32_t(cfg.sensors * cfg.frames * cfg.channels); }
    std::uint32_t planes_out() const { return std::uint32_t(cfg.sensors * cfg.channels); }
    // A new device buffer of count float32s; returns its device address.
    VkDeviceAddress floats(std::uint64_t count);
    // A new device buffer of count plane samples (float32, or float16 under
    // Precision::Fp16Storage: `Planes` in common.glsl); its device address.
    VkDeviceAddress planes(std::uint64_t count);
    // A small host-written buffer holding values (filter taps, ...); its address.
    VkDeviceAddress constants(const std::vector<float>& values);
    // The `bytes` (0: to the end of its buffer, or of the range of it in
    // `fixed`) starting at `address`: what Recorder::dispatch binds.
    DeviceSpan span(VkDeviceAddress address, VkDeviceSize bytes = 0) const;

private:
    Buffer& intermediate(VkDeviceSize bytes, MemoryUse use);
};

// Whether a multi-scale graph's largest buffer may exceed what one
// descriptor can bind (maxStorageBufferRange): it then runs the kernels'
// device-address variants.
bool needs_device_addresses(const PlanConfig& cfg, const VkPhysicalDeviceLimits& limits);
// At most the bytes of a multi-scale graph's largest buffer (proportional to
// its sensors): one plane set of every frame.
double largest_buffer_bytes(const PlanConfig& cfg);

// A cycle's input: the frames as uploaded (S*K frames, HWC, 8-bit or
// float32; shaders/frames.glsl) and, on first request, the same samples
// unpacked into planes (S*K*C planes of H x W, plane (s*K + k)*C + c) by an
// unpack pass recorded then. A graph whose first passes read the frames
// themselves never asks for the planes, and no unpack pass is recorded.
class FrameSource {
public:
    FrameSource(GraphBuilder& g, DeviceSpan frames) : g_(g), frames_(frames) {}
    DeviceSpan frames() const { return frames_; }
    // The push fields frames.glsl reads: pixels, channels, is_u8.
    PushConstants frame_fields() const;
    VkDeviceAddress planes();

private:
    GraphBuilder& g_;
    DeviceSpan frames_;
    VkDeviceAddress planes_ = 0;
};

// Records the fusion of the input and returns the address of the fused
// planes (S*C planes of H x W, plane s*C + c).
// Brovey, channel-sum and the mean read the frames as uploaded and write the
// fused image into `image` themselves (when given): no unpack, no pack.
// `kernel` is the method shaders/pointwise_fuse.comp is specialized for (a
// method's is in its Vulkan row), `stage` the name --profile reports.
inline constexpr std::uint32_t kPointwiseMean = VKFUSE_POINTWISE_MEAN;  // the background model's mean
VkDeviceAddress record_pointwise(GraphBuilder& g, DeviceSpan frames, std::optional<DeviceSpan> image,
                                 std::uint32_t kernel, const char* stage);
VkDeviceAddress record_laplacian(GraphBuilder& g, FrameSource& input);
VkDeviceAddress record_wavelet(GraphBuilder& g, FrameSource& input);


// A set of planes as a strided 2-D view: plane p's sample (y, x) is
// addr[p * plane_stride + y * row_stride + x], in plane samples. What the
// graph builders hand each other and their kernels.
struct PlaneView {
    VkDeviceAddress addr = 0;
    int row_stride = 0;
    std::uint32_t plane_stride = 0;
};

// The fused sensors one fusing dispatch covers (group_sensor in
// shaders/common.glsl): of sensors in blocks of `period`, members first ..
// first + count - 1 of every block. count 0: every sensor of the plan.
struct SensorGroup {
    std::uint32_t first = 0, count = 0, period = 0;
    SensorGroup in(const PlanConfig& cfg) const {
        return count ? *this : SensorGroup{0, std::uint32_t(cfg.sensors), std::uint32_t(cfg.sensors)};
    }
    // The group's push fields; the dispatch's z: its sensors times channels.
    PushConstants push(const PlanConfig& cfg) const;
    std::uint32_t planes(const PlanConfig& cfg) const;
};

// A width x height region of S*K*C source planes (plane (s*K + k)*C + c) and
// of the S*C fused planes (s*C + c), both with the same strides. Inside its
// top-left split_w x split_h corner the base rule applies, the detail rule
// elsewhere. With a table (S*K uint32), fused sensor s's frame k is source
// frame table[s*K + k] (planes table[s*K + k]*C + c) of any number of them.
// The top-left skip_w x skip_h corner is left unwritten. Only the fused
// sensors of `group` are written (their table frames among src's planes).
struct RuleFuseRegion {
    PlaneView src, dst;
    int width = 0, height = 0;
    int split_w = 0, split_h = 0;
    std::optional<DeviceSpan> table = std::nullopt;
    int skip_w = 0, skip_h = 0;
    SensorGroup group = {};
};
void record_rule_fuse(GraphBuilder& g, const RuleFuseRegion& region);

// A multi-scale method's coefficients decomposed once and fused in many
// combinations (study/cached_fusion.hpp). *_decompose records the
// decomposition of every frame of the input and returns its levels, each a
// view of the S*K*C planes of one level of every frame (plane f*C + c; a
// wavelet level holds each frame's coefficient block, approximation
// top-left; a Laplacian level its Gaussian G_l, G_0 the frame itself).
// A cache may be decomposed in groups of its sources, each group's planes
// in buffers one descriptor can bind (CachedSources). *_cached fuses the
// plan's sensors, blocks of `sources` (sensor b*sources + s fusing source s),
// from those levels, sensor j's frame k being frame table[j*K + k] among its
// source group's (S*K uint32), and returns the fused planes as record_* does.
struct CachedSources {
    std::uint32_t first = 0, count = 0;  // sources first .. first + count - 1
    std::vector<PlaneView> levels;       // *_decompose's, of these sources' frames alone
};
std::vector<PlaneView> record_wavelet_decompose(GraphBuilder& g, FrameSource& input);
VkDeviceAddress record_wavelet_cached(GraphBuilder& g, std::span<const CachedSources> groups, std::uint32_t sources,
                                      DeviceSpan table);
std::vector<PlaneView> record_laplacian_decompose(GraphBuilder& g, FrameSource& input);
VkDeviceAddress record_laplacian_cached(GraphBuilder& g, std::span<const CachedSources> groups, std::uint32_t sources,
                                        DeviceSpan table);

// Workgroups of the metric pass per sensor: each writes kMetricPartialFloats
// floats (shaders/metrics.comp).
inline constexpr std::uint32_t kMetricPartialFloats = 8;
std::uint32_t metric_groups(const PlanConfig& cfg);

// Records the metric pass over the fused planes; sensor s's partials land at
// partials, from float s * metric_groups * kMetricPartialFloats on.
// `image`, given only where metrics_write_image(), receives the fused image
// (HWC float32) from the same pass.
// Sensor s's background is the one of sensor s - s % background_group in
// `background` (1: its own; a cached fusion's group shares its first's).
void record_metrics(GraphBuilder& g, VkDeviceAddress fused, VkDeviceAddress background, DeviceSpan partials,
                    std::optional<DeviceSpan> image = std::nullopt, std::uint32_t background_group = 1);
// One sensor's metrics from its metric_groups partials, summed in double;
// each metric times 2^exponent (the scale its frames went to the device at).
// Partials holding a NaN or Inf throw as check_device_results does, naming
// `owner`: summed, a NaN would become a contrast of 0.
Metrics finish_metrics(std::span<const float> partials, const PlanConfig& cfg, int exponent, const std::string& owner);
// Throws ErrorKind::Numeric, naming `owner` ("sensor 2") and `what` ("a metric
// sum", "the fused image"), where `results` read back hold a NaN or Inf: the
// arithmetic left float32's range (float16's in an fp16 plan).
void check_device_results(const PlanConfig& cfg, const std::string& owner, std::span<const float> results,
                          const char* what);
// Whether the metric pass can write the read-back image too (rows of whole quads).
bool metrics_write_image(const PlanConfig& cfg);

}  // namespace vkfuse::vk

// Kernels reach their buffers through descriptor bindings, or through device
// addresses (KernelBuffers; and in plans where not even one sensor fits in
// maxStorageBufferRange):
// two builds of every kernel from one source (shaders/bindings.glsl). Both
// must give the same bits for every method, input type and shape, including
// shapes whose planes are not a multiple of four samples (the kernels' scalar
// paths). So must a plan recorded in blocks of its sensors, each block bound
// to its range of the buffers (vk/plan/sensor_blocks.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <cstring>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vk/plan/plan_impl.hpp"
#include "vk/plan/sensor_blocks.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/rig/background.hpp"

namespace vkfuse::test {
namespace {

struct Shape {
    int height, width, channels, frames, sensors;
    PixelType input;
    Precision precision = Precision::Fp32;
};

struct Results {
    std::vector<Image> fused;
    std::vector<Metrics> metrics;
    bool addressed = false;             // the plan ran the device-address kernels
    std::size_t intermediates = 0;      // device buffers the plan's graph made
};

std::vector<Image> float_frames(const Shape& s) {
    std::vector<Image> floats;
    for (int i = 0; i < s.sensors * s.frames; ++i)
        floats.push_back(convert<float>(structured_image(s.height, s.width, s.channels, 100 + std::uint32_t(i))));
    return floats;
}

PlanConfig config(const FusionSpec& spec, const Shape& s) {
    PlanConfig cfg;
    cfg.fusion = spec;
    cfg.height = s.height;
    cfg.width = s.width;
    cfg.channels = s.channels;
    cfg.frames = s.frames;
    cfg.sensors = s.sensors;
    cfg.input = s.input;
    cfg.metrics = MetricSet::all();
    cfg.precision = s.precision;
    return cfg;
}

// Every method, the wavelet in both of its border kinds.
std::vector<FusionSpec> method_specs() {
    std::vector<FusionSpec> specs;
    for (Method m : {Method::ChannelSum, Method::Brovey, Method::Laplacian}) {
        FusionSpec f;
        f.method = m;
        specs.push_back(f);
    }
    for (WaveletMode mode : {WaveletMode::Periodization, WaveletMode::Symmetric}) {
        FusionSpec f;
        f.method = Method::Wavelet;
        f.wavelet = Wavelet::Bior44;
        f.mode = mode;
        specs.push_back(f);
    }
    return specs;
}

// Whether the method runs on the shape and device at all.
bool applies(const FusionSpec& spec, const Shape& s, const Context& ctx) {
    if (s.channels != 3 && spec.method != Method::Laplacian && spec.method != Method::Wavelet) return false;
    if (spec.method == Method::ChannelSum && s.frames != 3) return false;
    return s.precision != Precision::Fp16Storage || ctx.device().fp16_storage;
}

std::string describe(const FusionSpec& spec, const Shape& s) {
    return std::string(to_string(spec.method)) + " " + std::to_string(s.height) + "x" + std::to_string(s.width) + "x" +
           std::to_string(s.channels) + " K" + std::to_string(s.frames) + " S" + std::to_string(s.sensors) +
           (s.input == PixelType::U8 ? " u8" : " f32") + (s.precision == Precision::Fp16Storage ? " fp16" : "");
}

// Images within `ulps` of each other (of the larger magnitude): the same bits at 0.
void expect_within_ulps(const std::vector<float>& a, const std::vector<float>& b, double ulps, const std::string& what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    if (ulps == 0) {
        EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float))) << what;
        return;
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
        const float larger = std::max(std::fabs(a[i]), std::fabs(b[i]));
        const double ulp = double(std::nextafter(larger, INFINITY) - larger);
        ASSERT_LE(std::fabs(double(a[i]) - double(b[i])), ulps * ulp) << what << " at " << i;
    }
}

void expect_close_metric(double a, double b, double ulps, const std::string& what) {
    if (ulps == 0)
        EXPECT_EQ(a, b) << what;
    else
        EXPECT_LE(std::fabs(a - b), 1e-5 * std::max(std::fabs(a), std::fabs(b)) + 1e-12) << what;
}

// Results of differently compiled kernels (bound and addressed variants):
// the same bits on a CPU device, within module_ulps() on a GPU.
void expect_same_results(const Results& a, const Results& b, double ulps, const std::string& what) {
    ASSERT_EQ(a.fused.size(), b.fused.size()) << what;
    for (std::size_t sensor = 0; sensor < a.fused.size(); ++sensor) {
        const std::string where = what + " sensor " + std::to_string(sensor);
        expect_within_ulps(a.fused[sensor].data, b.fused[sensor].data, ulps, where);
        const Metrics& ma = a.metrics[sensor];
        const Metrics& mb = b.metrics[sensor];
        expect_close_metric(ma.sharpness, mb.sharpness, ulps, where + " sharpness");
        expect_close_metric(ma.contrast, mb.contrast, ulps, where + " contrast");
        ASSERT_EQ(ma.background_diff.has_value(), mb.background_diff.has_value()) << where;
        if (ma.background_diff)
            expect_close_metric(*ma.background_diff, *mb.background_diff, ulps, where + " background diff");
    }
}

Results run(Context& ctx, const FusionSpec& spec, const Shape& s) {
    Plan plan(ctx, config(spec, s));
    const std::vector<Image> floats = float_frames(s);
    std::vector<std::vector<std::uint8_t>> bytes;
    std::vector<FrameView> views;
    for (const Image& f : floats) {
        std::vector<std::uint8_t> b;
        for (float v : f.data) b.push_back(std::uint8_t(v * 255.0f + 0.5f));
        bytes.push_back(std::move(b));
    }
    for (int i = 0; i < s.sensors * s.frames; ++i)
        views.push_back(s.input == PixelType::U8
                            ? FrameView{bytes[std::size_t(i)].data(), s.height, s.width, s.channels, PixelType::U8}
                            : FrameView::of(floats[std::size_t(i)]));
    for (int sensor = 0; sensor < s.sensors; ++sensor)
        plan.set_background(sensor,
                            FrameView::of(convert<float>(random_image(s.height, s.width, s.channels, 7 + std::uint32_t(sensor)))));
    plan.run(views);
    Results r;
    r.addressed = vk::PlanAccess::of(plan).addressed;
    r.intermediates = vk::PlanAccess::of(plan).buffers.size();
    for (int sensor = 0; sensor < s.sensors; ++sensor) {
        r.fused.push_back(plan.fused(sensor));
        r.metrics.push_back(plan.metrics(sensor));
    }
    return r;
}

class VulkanBufferAccess : public VulkanTest {};

TEST_F(VulkanBufferAccess, BoundAndAddressedKernelsGiveTheSameBits) {
    SKIP_WITHOUT_DEVICE_ADDRESSES();
    const Shape shapes[] = {{96, 256, 3, 3, 2, PixelType::U8},  // planes of whole quads
                            {96, 128, 3, 3, 1, PixelType::F32},
                            {75, 77, 3, 3, 2, PixelType::U8},  // 5775 pixels: the scalar paths
                            {75, 77, 1, 2, 1, PixelType::F32},
                            {96, 256, 3, 3, 1, PixelType::U8, Precision::Fp16Storage},  // float16 planes
                            {75, 77, 3, 2, 1, PixelType::F32, Precision::Fp16Storage}};
    for (const FusionSpec& spec : method_specs())
        for (const Shape& s : shapes)
            if (applies(spec, s, ctx()))
                expect_same_results(run(bound_context(), spec, s), run(addressed_context(), spec, s),
                                    module_ulps(ctx()), describe(spec, s));
}

// KernelBuffers decides how every dispatch reaches its buffers: Auto takes
// addresses on a CPU device that has them, bindings elsewhere; a plan of
// bound kernels writes a descriptor set per dispatch, one of addressed kernels none.
TEST_F(VulkanBufferAccess, KernelBuffersDecideHowEveryDispatchReachesItsBuffers) {
    SKIP_WITHOUT_DEVICE_ADDRESSES();
    ContextOptions o = validated_options();
    o.kernel_buffers = KernelBuffers::Addresses;
    Context addresses(o);
    EXPECT_EQ(addresses.kernel_buffers(), KernelBuffers::Addresses);
    EXPECT_EQ(bound_context().kernel_buffers(), KernelBuffers::Bound);
    if (!std::getenv("VKFUSE_KERNEL_BUFFERS")) {
        EXPECT_EQ(ctx().kernel_buffers(),
                  ctx().device().type == "cpu" ? KernelBuffers::Addresses : KernelBuffers::Bound);
    }
    for (const FusionSpec& spec : method_specs()) {
        const PlanConfig cfg = config(spec, Shape{96, 256, 3, 3, 2, PixelType::U8});
        Plan by_address(addresses, cfg), bound(bound_context(), cfg);
        EXPECT_EQ(vk::PlanAccess::of(by_address).sets->written(), 0u) << to_string(spec.method);
        EXPECT_GT(vk::PlanAccess::of(bound).sets->written(), 0u) << to_string(spec.method);
        EXPECT_FALSE(vk::PlanAccess::of(by_address).addressed) << "one chain, not blocks, only with device_addresses_only";
    }
}

// A plan whose buffers exceed one binding is recorded in blocks of sensors.
// Here the device's binding range is narrowed to 4.5 sensors' largest buffer,
// so 9 sensors run as blocks of 4, 4 and 1 where every per-sensor buffer's
// stride keeps block offsets aligned, and through device addresses where not.
TEST_F(VulkanBufferAccess, SensorBlocksGiveTheBitsOfOneBlock) {
    Context narrow(validated_options());
    struct Case {
        Shape shape;
        bool bound;  // block offsets can be aligned: the blocks are bound
    };
    const Case cases[] = {{{96, 256, 3, 3, 9, PixelType::U8}, true},
                          {{96, 256, 3, 3, 9, PixelType::F32}, true},  // Brovey's thresholds: 4 bytes a sensor
                          {{75, 77, 3, 3, 9, PixelType::U8}, false},   // odd frame bytes: no aligned block
                          {{96, 256, 3, 3, 9, PixelType::U8, Precision::Fp16Storage}, true}};
    auto& limits = vk::ContextAccess::of(narrow).properties.limits;
    const std::uint32_t full_range = limits.maxStorageBufferRange;
    // The cases' `bound` holds for offsets aligned to 16 bytes (lavapipe's);
    // a profile's coarser alignment may leave a case no aligned block.
    const bool fine_alignment = limits.minStorageBufferOffsetAlignment <= 16;
    for (const FusionSpec& spec : method_specs())
        for (const Case& c : cases) {
            const Shape& s = c.shape;
            if (!applies(spec, s, ctx())) continue;
            if (!c.bound && !has_device_addresses()) continue;  // such blocks need addresses
            PlanConfig one = config(spec, s);
            one.sensors = 1;
            limits.maxStorageBufferRange = std::uint32_t(vk::plan_buffer_bytes(one, vk::PlanKind::Fuse) * 4.5);
            const Results blocks = run(narrow, spec, s);
            limits.maxStorageBufferRange = full_range;
            const Results whole = run(ctx(), spec, s);
            const std::string what = describe(spec, s);
            ASSERT_FALSE(whole.addressed) << what;
            if (fine_alignment) {
                EXPECT_EQ(blocks.addressed, !c.bound) << what;
            }
            // The blocks share one block's intermediates.
            if (!blocks.addressed) {
                EXPECT_EQ(blocks.intermediates, whole.intermediates) << what;
            }
            // Addressed blocks run other modules than the bound whole.
            expect_same_results(blocks, whole, blocks.addressed ? module_ulps(ctx()) : 0, what);
        }
}

// A skipping plan stays one block: its change detection binds per-sensor
// means of 2K floats a pixel beside the frames, beyond what a pointwise
// method's own buffers take. Between the two it must take device addresses.
TEST_F(VulkanBufferAccess, SkippingPlansBeyondOneBindingTakeDeviceAddresses) {
    SKIP_WITHOUT_DEVICE_ADDRESSES();
    Context narrow(validated_options());
    FusionSpec brovey;
    brovey.method = Method::Brovey;
    PlanConfig cfg = config(brovey, Shape{96, 256, 3, 3, 4, PixelType::U8});
    cfg.skip.policy = SkipPolicy::Idle;
    const double samples = double(cfg.sensors) * cfg.height * cfg.width * cfg.channels;
    // Room for the frames and the fused planes (4 bytes a sample), not for
    // the means (2K floats a sample).
    vk::ContextAccess::of(narrow).properties.limits.maxStorageBufferRange = std::uint32_t(samples * 5);
    std::optional<Plan> plan;
    ASSERT_NO_THROW(plan.emplace(narrow, cfg));
    EXPECT_TRUE(vk::PlanAccess::of(*plan).addressed);
}

// Barriers only between dependent dispatches: one that neither writes what
// the dispatches since the last barrier reached nor reaches what they wrote
// needs none (a Laplacian pyramid's levels of rows that are not whole pairs
// of quads, here every level, are fused independently before the collapse
// walks them from the top). The synchronization validation on every Vulkan
// test checks that none needed is missing, and the results are every other
// test's.
TEST_F(VulkanBufferAccess, IndependentDispatchesShareABarrier) {
    FusionSpec spec;
    spec.method = Method::Laplacian;
    spec.levels = 4;
    PlanConfig cfg = config(spec, Shape{96, 100, 3, 3, 1, PixelType::U8});
    Plan plan(ctx(), cfg);
    const auto& im = vk::PlanAccess::of(plan);
    EXPECT_GT(im.dispatches, 8u);
    std::printf("4-level Laplacian plan: %u dispatches, %u barriers\n", im.dispatches, im.barriers);
    EXPECT_LE(im.barriers + 3, im.dispatches - 1) << im.barriers << " barriers, " << im.dispatches << " dispatches";
    const Results r = run(ctx(), spec, Shape{96, 100, 3, 3, 1, PixelType::U8});
    EXPECT_EQ(r.fused.size(), 1u);
}

// Profiling a plan of many blocks: every block's stages are timed (the query
// pool grows with the blocks) and each stage is reported once, summed.
TEST_F(VulkanBufferAccess, ProfiledBlocksReportEachStageOnce) {
    Context narrow(validated_options());
    FusionSpec spec;
    spec.method = Method::Laplacian;
    spec.levels = 2;
    const Shape s{32, 64, 3, 3, 120, PixelType::U8};
    PlanConfig cfg = config(spec, s);
    cfg.metrics = {};  // 5 stages a block, with pack
    cfg.profile = true;
    PlanConfig one = cfg;
    one.sensors = 1;
    vk::ContextAccess::of(narrow).properties.limits.maxStorageBufferRange =
        std::uint32_t(vk::plan_buffer_bytes(one, vk::PlanKind::Fuse) * 1.5);
    Plan blocks(narrow, cfg);
    ASSERT_FALSE(vk::PlanAccess::of(blocks).addressed);
    ASSERT_EQ(vk::PlanAccess::of(blocks).blocks(), 120u);
    cfg.profile = false;
    Plan whole(ctx(), cfg);
    const std::vector<Image> floats = float_frames(s);
    std::vector<std::vector<std::uint8_t>> bytes;
    std::vector<FrameView> views;
    for (const Image& f : floats) {
        std::vector<std::uint8_t>& b = bytes.emplace_back();
        for (float v : f.data) b.push_back(std::uint8_t(v * 255.0f + 0.5f));
    }
    for (auto& b : bytes) views.push_back(FrameView{b.data(), s.height, s.width, s.channels, PixelType::U8});
    blocks.run(views);
    whole.run(views);
    std::vector<std::string> names;
    for (const KernelTime& k : blocks.profile()) {
        EXPECT_EQ(std::count(names.begin(), names.end(), k.name), 0) << k.name;
        EXPECT_GE(k.ms, 0.0) << k.name;
        names.push_back(k.name);
    }
    EXPECT_EQ(names, (std::vector<std::string>{"unpack", "pyr_down", "lap_fuse", "lap_fuse_collapse", "pack"}));
    for (int sensor = 0; sensor < s.sensors; ++sensor)
        EXPECT_EQ(0, std::memcmp(blocks.fused(sensor).data.data(), whole.fused(sensor).data.data(),
                                 whole.fused(sensor).data.size() * sizeof(float)))
            << "sensor " << sensor;
}

// The background model's mean, a plan kind of its own (float32 planes, one sensor).
TEST_F(VulkanBufferAccess, BackgroundMeanBoundAndAddressedGiveTheSameBits) {
    SKIP_WITHOUT_DEVICE_ADDRESSES();
    for (const Shape& s : {Shape{96, 256, 3, 5, 1, PixelType::F32}, Shape{75, 77, 1, 3, 1, PixelType::F32}}) {
        const std::vector<Image> floats = float_frames(s);
        std::vector<FrameView> views;
        for (const Image& f : floats) views.push_back(FrameView::of(f));
        BackgroundModel bound(ctx(), s.height, s.width, s.channels, s.frames, PixelType::F32);
        BackgroundModel addressed(addressed_context(), s.height, s.width, s.channels, s.frames, PixelType::F32);
        const Image a = bound.mean(views), b = addressed.mean(views);
        expect_within_ulps(a.data, b.data, module_ulps(ctx()),
                           std::to_string(s.height) + "x" + std::to_string(s.width) + "x" + std::to_string(s.channels));
    }
}

}  // namespace
}  // namespace vkfuse::test

// Simulated device profiles (ContextOptions::device_profile) on whatever
// device the tests run on: each profile's limits and memory are in force and
// what vkfuse adapts to them still fuses like the reference. The whole vulkan
// label also runs under each profile (VKFUSE_DEVICE_PROFILE, tools/gpu_profiles.sh).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "test_support.hpp"
#include "vk/engine/buffer.hpp"
#include "vk/engine/context_impl.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

constexpr double kFusedTolerance = 1e-5;  // docs/spec.md: Vulkan vs reference
constexpr double kMetricTolerance = 1e-4;  // relative

ContextOptions with_profile(const std::string& name) {
    ContextOptions o = validated_options();
    o.device_profile = name;
    return o;
}

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
    for (const std::string& l : lines)
        if (l.find(text) != std::string::npos) return true;
    return false;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string all;
    for (const std::string& l : lines) all += l + "\n";
    return all;
}

// Every method on two sensors with all three metrics, run twice on different
// frames (a read-back that is not invalidated would show the first run's),
// against the double reference.
void expect_methods_match_reference(Context& ctx) {
    const int h = 48, w = 64, c = 3, K = 3, S = 2;  // two levels of bior4.4
    for (Method m : {Method::ChannelSum, Method::Brovey, Method::Laplacian, Method::Wavelet}) {
        SCOPED_TRACE(std::string(to_string(m)));
        PlanConfig cfg;
        cfg.fusion.method = m;
        cfg.fusion.detail_rule = Rule::Mean;  // no max-abs near-ties to allow for
        cfg.fusion.levels = 2;
        cfg.height = h;
        cfg.width = w;
        cfg.channels = c;
        cfg.frames = K;
        cfg.sensors = S;
        cfg.metrics = {Metric::Sharpness, Metric::Contrast, Metric::BackgroundDiff};
        Plan plan(ctx, cfg);
        const ImageD background = structured_image(h, w, c, 7);
        const Image background_f = convert<float>(background);
        for (int s = 0; s < S; ++s) plan.set_background(s, FrameView::of(background_f));
        for (std::uint32_t run = 0; run < 2; ++run) {
            std::vector<ImageD> frames;
            std::vector<Image> floats;
            std::vector<FrameView> views;
            for (int i = 0; i < K * S; ++i) {
                frames.push_back(i % 2 ? random_image(h, w, c, 100 * run + i) : structured_image(h, w, c, 100 * run + i));
                floats.push_back(convert<float>(frames.back()));
            }
            for (const Image& f : floats) views.push_back(FrameView::of(f));
            plan.run(views);
            for (int s = 0; s < S; ++s) {
                const std::vector<ImageD> own(frames.begin() + s * K, frames.begin() + (s + 1) * K);
                const ImageD ref = fuse_reference(own, cfg.fusion);
                EXPECT_LE(max_abs_diff(plan.fused(s), ref), kFusedTolerance) << "run " << run << " sensor " << s;
                const Metrics want = metrics_reference(convert<double>(plan.fused(s)), &background, cfg.metrics);
                const Metrics got = plan.metrics(s);
                EXPECT_NEAR(got.sharpness, want.sharpness, kMetricTolerance * std::fabs(want.sharpness));
                EXPECT_NEAR(got.contrast, want.contrast, kMetricTolerance * std::fabs(want.contrast));
                EXPECT_NEAR(*got.background_diff, *want.background_diff, kMetricTolerance * std::fabs(*want.background_diff));
            }
        }
    }
}

class VulkanDeviceProfiles : public VulkanTest {};

TEST(DeviceProfiles, NamesInTheOrderInfoListsThem) {
    EXPECT_EQ(device_profile_names(), (std::vector<std::string>{"discrete-no-rebar", "phone", "no-device-address"}));
}

TEST_F(VulkanDeviceProfiles, AnUnknownNameIsRefusedWithTheKnownOnes) {
    expect_error([] { Context c(with_profile("gpu9000")); }, "device profile=gpu9000", ErrorKind::InvalidArgument,
                 "no such device profile (discrete-no-rebar, phone, no-device-address)");
}

TEST_F(VulkanDeviceProfiles, EachProfileSaysWhatItIsAndFusesLikeTheReference) {
    for (const std::string& name : device_profile_names()) {
        SCOPED_TRACE(name);
        Context ctx(with_profile(name));
        EXPECT_EQ(ctx.device_profile(), name);
        const std::vector<std::string> adapted = ctx.adaptations();
        ASSERT_FALSE(adapted.empty());
        EXPECT_EQ(adapted.front().rfind("device profile " + name + " (simulated on ", 0), 0u) << adapted.front();
        expect_methods_match_reference(ctx);
        EXPECT_EQ(ctx.validation_message_count(), 0u);
    }
}

// Four storage buffers a stage: the set layout has four bindings, and the
// kernels that bind more (metrics, the wavelet's fusing passes) reach their
// buffers by address; the fusion above ran them.
TEST_F(VulkanDeviceProfiles, APhoneBindsFourBuffersAndAddressesTheRest) {
    Context ctx(with_profile("phone"));
    const auto& impl = vk::ContextAccess::of(ctx);
    EXPECT_EQ(impl.bound_buffers, 4u);
    EXPECT_EQ(impl.properties.limits.minStorageBufferOffsetAlignment, 256u);
    EXPECT_EQ(impl.properties.limits.maxStorageBufferRange, 128u << 20);
    EXPECT_TRUE(mentions(ctx.adaptations(), "kernels binding more than 4 storage buffers")) << joined(ctx.adaptations());
}

TEST_F(VulkanDeviceProfiles, WithoutDeviceAddressesEveryKernelBinds) {
    Context ctx(with_profile("no-device-address"));
    EXPECT_FALSE(ctx.device().device_addresses);
    EXPECT_TRUE(mentions(ctx.adaptations(), "every kernel binds its buffers")) << joined(ctx.adaptations());
    EXPECT_EQ(ctx.kernel_buffers(), KernelBuffers::Bound);
    ContextOptions o = with_profile("no-device-address");
    o.device_addresses_only = true;
    expect_error([&] { Context c(o); }, ctx.device().name, ErrorKind::Device,
                 "device_addresses_only asked for, but the device has no bufferDeviceAddress");
    o.device_addresses_only = false;
    o.kernel_buffers = KernelBuffers::Addresses;
    expect_error([&] { Context c(o); }, ctx.device().name, ErrorKind::Device,
                 "kernel buffers through addresses asked for, but the device has no bufferDeviceAddress");
}

// A 40-sensor QVGA K=3 skipping plan as `vkfuse run` makes one (static
// reuse, background difference) takes about 157 MB of a 256 MiB BAR heap for
// what the host writes; a second one must still build, the rest of its
// uploads in system memory.
TEST_F(VulkanDeviceProfiles, TwoFortySensorSkippingPlansOutgrowTheBarHeap) {
    Context ctx(with_profile("discrete-no-rebar"));
    PlanConfig cfg;
    cfg.height = 240;
    cfg.width = 320;
    cfg.channels = 3;
    cfg.frames = 3;
    cfg.sensors = 40;
    cfg.input = PixelType::U8;
    cfg.skip.policy = SkipPolicy::Static;
    cfg.metrics = {Metric::Sharpness, Metric::Contrast, Metric::BackgroundDiff};
    std::optional<Plan> first, second;
    ASSERT_NO_THROW(first.emplace(ctx, cfg));
    ASSERT_NO_THROW(second.emplace(ctx, cfg));
    const auto& memory = vk::ContextAccess::of(ctx).memory_types;
    EXPECT_LE(memory.heap_used(2), VkDeviceSize(256) << 20);
    EXPECT_GT(memory.heap_used(1), 0u);
    EXPECT_TRUE(mentions(ctx.adaptations(), "device-local host-visible heap 2 (256 MiB) was full; buffers went to the "
                                            "system heap 1"))
        << joined(ctx.adaptations());
}

// With the host-visible window full, each plan's frames land in system
// memory and are copied into device-local memory before its kernels run.
TEST_F(VulkanDeviceProfiles, FramesInSystemMemoryAreStagedIntoDeviceMemory) {
    Context ctx(with_profile("discrete-no-rebar"));
    const vk::Buffer window(vk::ContextAccess::of(ctx), VkDeviceSize(256) << 20, vk::MemoryUse::Upload);
    EXPECT_EQ(window.heap(), 2u);
    EXPECT_TRUE(window.device_local());
    expect_methods_match_reference(ctx);
    EXPECT_TRUE(mentions(ctx.adaptations(), "copied into device-local memory before each cycle")) << joined(ctx.adaptations());
    EXPECT_EQ(ctx.validation_message_count(), 0u);
}

std::uint64_t vkfuse_bytes(const Context& ctx) {
    std::uint64_t sum = 0;
    for (const MemoryHeap& h : ctx.memory_heaps()) sum += h.vkfuse_bytes;
    return sum;
}

// Every heap says what this context allocated from it (a plan's buffers, and
// nothing once the plan is gone), and its budget where the device reports one.
TEST_F(VulkanDeviceProfiles, HeapsSayWhatVkfuseAllocatedFromEach) {
    Context ctx(validated_options());
    const std::vector<MemoryHeap> heaps = ctx.memory_heaps();
    ASSERT_FALSE(heaps.empty());
    for (const MemoryHeap& h : heaps) {
        EXPECT_GT(h.bytes, 0u);
        if (h.budget) {
            EXPECT_GT(*h.budget, 0u);
        }
    }
    const std::uint64_t before = vkfuse_bytes(ctx);
    {
        PlanConfig cfg;
        cfg.height = 240;
        cfg.width = 320;
        cfg.frames = 3;
        cfg.sensors = 4;
        Plan plan(ctx, cfg);
        const std::uint64_t frames = std::uint64_t(4) * 3 * 240 * 320 * 3 * sizeof(float);
        EXPECT_GE(vkfuse_bytes(ctx), before + frames);
    }
    EXPECT_EQ(vkfuse_bytes(ctx), before);
    Context discrete(with_profile("discrete-no-rebar"));
    const std::vector<MemoryHeap> simulated = discrete.memory_heaps();
    ASSERT_EQ(simulated.size(), 3u);
    EXPECT_EQ(simulated[2].bytes, std::uint64_t(256) << 20);
    EXPECT_TRUE(simulated[2].device_local && simulated[2].host_visible);
    EXPECT_FALSE(simulated[0].host_visible);
    EXPECT_FALSE(simulated[2].budget.has_value());  // a simulated heap has no reported budget
}

TEST(FilterArithmeticNames, ParseAsInfoAndTheEnvironmentSpellThem) {
    EXPECT_EQ(parse_filter_arithmetic("compensated-float32"), FilterArithmetic::CompensatedFloat32);
    EXPECT_EQ(parse_filter_arithmetic("compensated float32"), FilterArithmetic::CompensatedFloat32);
    EXPECT_EQ(parse_filter_arithmetic("float64"), FilterArithmetic::Float64);
    EXPECT_EQ(parse_filter_arithmetic("auto"), FilterArithmetic::Auto);
    EXPECT_EQ(parse_filter_arithmetic("double"), std::nullopt);
}

TEST_F(VulkanDeviceProfiles, TheEnvironmentPicksTheArithmeticAndABadOneIsRefused) {
    ::setenv("VKFUSE_FILTER_ARITHMETIC", "compensated-float32", 1);
    {
        Context ctx(validated_options());
        EXPECT_EQ(ctx.filter_arithmetic(), FilterArithmetic::CompensatedFloat32);
    }
    ::setenv("VKFUSE_FILTER_ARITHMETIC", "fast", 1);
    expect_error([] { Context c(validated_options()); }, "VKFUSE_FILTER_ARITHMETIC=fast", ErrorKind::InvalidArgument,
                 "expected auto, float64 or compensated-float32");
    ::unsetenv("VKFUSE_FILTER_ARITHMETIC");
}

TEST_F(VulkanDeviceProfiles, TheEnvironmentPicksHowKernelsReachBuffersAndABadWayIsRefused) {
    const char* before = std::getenv("VKFUSE_KERNEL_BUFFERS");
    const std::string kept = before ? before : "";
    ::setenv("VKFUSE_KERNEL_BUFFERS", "bound", 1);
    {
        Context ctx(validated_options());
        EXPECT_EQ(ctx.kernel_buffers(), KernelBuffers::Bound);
    }
    ::setenv("VKFUSE_KERNEL_BUFFERS", "descriptors", 1);
    expect_error([] { Context c(validated_options()); }, "VKFUSE_KERNEL_BUFFERS=descriptors",
                 ErrorKind::InvalidArgument, "expected auto, bound or addresses");
    if (before)
        ::setenv("VKFUSE_KERNEL_BUFFERS", kept.c_str(), 1);
    else
        ::unsetenv("VKFUSE_KERNEL_BUFFERS");
    EXPECT_EQ(parse_kernel_buffers("addresses"), KernelBuffers::Addresses);
    EXPECT_EQ(parse_kernel_buffers("auto"), KernelBuffers::Auto);
    EXPECT_EQ(parse_kernel_buffers("bindings"), std::nullopt);
}

// The context asks the device whether fma is fused before it builds a
// compensated kernel (lavapipe's is not: Mesa 25's llvmpipe returns 0 for
// fma(a, b, -a*b)), and splits products where it is not or when asked. The
// precision tests hold the split to the same bounds (filter_arithmetic_contexts).
TEST_F(VulkanDeviceProfiles, ProductsAreSplitWhereFmaIsNotFusedOrWhenAsked) {
    ContextOptions o = validated_options();
    o.filter_arithmetic = FilterArithmetic::CompensatedFloat32;
    {
        Context ctx(o);
        const bool split = ctx.splits_products();  // asks the device (once)
        EXPECT_EQ(split, mentions(ctx.adaptations(), "fma is not fused")) << joined(ctx.adaptations());
    }
    o.split_products = true;
    Context split(o);
    EXPECT_TRUE(split.splits_products());
    EXPECT_TRUE(mentions(split.adaptations(), "asked to split products")) << joined(split.adaptations());
    o.filter_arithmetic = FilterArithmetic::Float64;
    if (split.device().float64) {
        EXPECT_FALSE(Context(o).splits_products());
    }
}

}  // namespace
}  // namespace vkfuse::test

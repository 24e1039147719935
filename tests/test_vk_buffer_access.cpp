// Kernels reach their buffers through descriptor bindings, or, in plans beyond
// maxStorageBufferRange, through device addresses: two builds of every kernel
// from one source (shaders/bindings.glsl). Both must give the same bits for
// every method, input type and shape, including shapes whose planes are not a
// multiple of four samples (the kernels' scalar paths).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "test_support.hpp"
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
};

std::vector<Image> float_frames(const Shape& s) {
    std::vector<Image> floats;
    for (int i = 0; i < s.sensors * s.frames; ++i)
        floats.push_back(convert<float>(structured_image(s.height, s.width, s.channels, 100 + std::uint32_t(i))));
    return floats;
}

Results run(Context& ctx, const FusionSpec& spec, const Shape& s) {
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
    Plan plan(ctx, cfg);
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
    const Image bg = convert<float>(random_image(s.height, s.width, s.channels, 7));
    for (int sensor = 0; sensor < s.sensors; ++sensor) plan.set_background(sensor, FrameView::of(bg));
    plan.run(views);
    Results r;
    for (int sensor = 0; sensor < s.sensors; ++sensor) {
        r.fused.push_back(plan.fused(sensor));
        r.metrics.push_back(plan.metrics(sensor));
    }
    return r;
}

class VulkanBufferAccess : public VulkanTest {};

TEST_F(VulkanBufferAccess, BoundAndAddressedKernelsGiveTheSameBits) {
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
    const Shape shapes[] = {{96, 256, 3, 3, 2, PixelType::U8},  // planes of whole quads
                            {96, 128, 3, 3, 1, PixelType::F32},
                            {75, 77, 3, 3, 2, PixelType::U8},  // 5775 pixels: the scalar paths
                            {75, 77, 1, 2, 1, PixelType::F32},
                            {96, 256, 3, 3, 1, PixelType::U8, Precision::Fp16Storage},  // float16 planes
                            {75, 77, 3, 2, 1, PixelType::F32, Precision::Fp16Storage}};
    for (const FusionSpec& spec : specs)
        for (const Shape& s : shapes) {
            if (s.channels != 3 && spec.method != Method::Laplacian && spec.method != Method::Wavelet) continue;
            if (spec.method == Method::ChannelSum && s.frames != 3) continue;
            if (s.precision == Precision::Fp16Storage && !ctx().device().fp16_storage) continue;
            const std::string what = std::string(to_string(spec.method)) + " " + std::to_string(s.height) + "x" +
                                     std::to_string(s.width) + "x" + std::to_string(s.channels) + " K" +
                                     std::to_string(s.frames) + " S" + std::to_string(s.sensors) +
                                     (s.input == PixelType::U8 ? " u8" : " f32") +
                                     (s.precision == Precision::Fp16Storage ? " fp16" : "");
            const Results bound = run(ctx(), spec, s);
            const Results addressed = run(addressed_context(), spec, s);
            for (int sensor = 0; sensor < s.sensors; ++sensor) {
                const Image& a = bound.fused[std::size_t(sensor)];
                const Image& b = addressed.fused[std::size_t(sensor)];
                ASSERT_EQ(a.data.size(), b.data.size()) << what;
                EXPECT_EQ(0, std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)))
                    << what << " sensor " << sensor;
                const Metrics& ma = bound.metrics[std::size_t(sensor)];
                const Metrics& mb = addressed.metrics[std::size_t(sensor)];
                EXPECT_EQ(ma.sharpness, mb.sharpness) << what;
                EXPECT_EQ(ma.contrast, mb.contrast) << what;
                EXPECT_EQ(ma.background_diff, mb.background_diff) << what;
            }
        }
}

// The background model's mean, a plan kind of its own (float32 planes, one sensor).
TEST_F(VulkanBufferAccess, BackgroundMeanBoundAndAddressedGiveTheSameBits) {
    for (const Shape& s : {Shape{96, 256, 3, 5, 1, PixelType::F32}, Shape{75, 77, 1, 3, 1, PixelType::F32}}) {
        const std::vector<Image> floats = float_frames(s);
        std::vector<FrameView> views;
        for (const Image& f : floats) views.push_back(FrameView::of(f));
        BackgroundModel bound(ctx(), s.height, s.width, s.channels, s.frames, PixelType::F32);
        BackgroundModel addressed(addressed_context(), s.height, s.width, s.channels, s.frames, PixelType::F32);
        const Image a = bound.mean(views), b = addressed.mean(views);
        ASSERT_EQ(a.data.size(), b.data.size());
        EXPECT_EQ(0, std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)))
            << s.height << "x" << s.width << "x" << s.channels;
    }
}

}  // namespace
}  // namespace vkfuse::test

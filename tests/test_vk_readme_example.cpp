// The README's library example, compiled and run so the documentation cannot rot.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "vk_fixture.hpp"

namespace vkfuse::test {
namespace {

// --- README example begins ---
// Fuse the paper's best pair, (15,15,15) + (0,15,0), for 4 sensors per cycle.
Plan make_plan(Context& ctx) {
    PlanConfig cfg;
    cfg.fusion.method = Method::Wavelet;  // bior4.4, 3 levels, mean / max-abs
    cfg.height = 240;
    cfg.width = 320;
    cfg.channels = 3;
    cfg.frames = 2;   // K illuminations per cycle
    cfg.sensors = 4;  // S sensors in one submit
    cfg.input = PixelType::U8;
    return Plan(ctx, cfg);  // pipelines, buffers, recorded commands: once
}

void cycle(Plan& plan, const std::vector<std::vector<std::uint8_t>>& camera_frames) {
    std::vector<FrameView> views;  // sensor-major: s * K + k
    for (auto& f : camera_frames) views.push_back({f.data(), 240, 320, 3, PixelType::U8});
    plan.run(views);  // one submit for every sensor
    for (int s = 0; s < 4; ++s) {
        Metrics m = plan.metrics(s);
        const Image& fused = plan.fused(s);  // 240 x 320 x 3 float, unclamped
        std::printf("sensor %d: sharpness %.6f contrast %.6f (%zu values)\n", s, m.sharpness, m.contrast, fused.size());
    }
}
// --- README example ends ---

class ReadmeExample : public VulkanTest {};

TEST_F(ReadmeExample, RunsAndScoresEverySensor) {
    std::vector<std::vector<std::uint8_t>> frames;
    for (int i = 0; i < 8; ++i) {
        ImageD img = structured_image(240, 320, 3, std::uint32_t(i));
        std::vector<std::uint8_t> bytes;
        for (double v : img.data) bytes.push_back(std::uint8_t(v * 255.0 + 0.5));
        frames.push_back(bytes);
    }
    Plan plan = make_plan(ctx());
    cycle(plan, frames);
    for (int s = 0; s < 4; ++s) {
        EXPECT_GT(plan.metrics(s).sharpness, 0.0);
        EXPECT_GT(plan.metrics(s).contrast, 0.0);
    }
}

}  // namespace
}  // namespace vkfuse::test

// Per-sensor wiring of the background in the rig: three sensors whose
// backgrounds differ clearly (each took its background with something else
// pressed into the gel) must each report the difference of its own fused
// frame with its own background: mean |I - B| over pixels and channels, with
// B the sensor's background means (one per setting) fused like its frames.
// The expected value is computed here on the CPU from the rig's own fused
// frame and the frames the rig handed to on_background.
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>
#include <string>

#include "rig_support.hpp"
#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/rig/background.hpp"

namespace vkfuse::test {
namespace {

double mean_abs_difference(const Image& fused, const ImageD& background) {
    EXPECT_TRUE(fused.height == background.height && fused.width == background.width &&
                fused.channels == background.channels);
    double sum = 0;
    for (std::size_t i = 0; i < background.data.size(); ++i) sum += std::abs(double(fused.data[i]) - background.data[i]);
    return sum / double(background.data.size());
}

void check_backgrounds(Context* context) {
    const IlluminationSequence seq = parse_sequence("15,15,15+0,15,0+15,0,0");
    const std::vector<std::string> background_objects{"nothing", "ball", "lego"};
    std::vector<SimRigSensor> sims;
    std::vector<RigSensor> sensors;
    for (int i = 0; i < 3; ++i) {
        sims.push_back(sim_sensor(i + 1, 0.02, background_objects[std::size_t(i)]));
        sensors.push_back({sims.back().sim, sims.back().clock});
    }
    std::mutex mutex;
    std::vector<std::vector<ImageD>> means(3, std::vector<ImageD>(seq.size()));
    RigConfig cfg;
    cfg.sequence = seq;
    cfg.fusion.method = Method::Laplacian;
    cfg.background_frames = 2;
    cfg.on_background = [&](std::size_t sensor, const Illumination& setting, const std::vector<Frame>& frames) {
        std::vector<FrameView> views;
        for (const Frame& f : frames) views.push_back(f.view());
        const ImageD mean = background_mean_reference(views);
        std::lock_guard lock(mutex);
        for (std::size_t k = 0; k < seq.size(); ++k)
            if (seq[k] == setting) means[sensor][k] = mean;
    };
    cfg.after_background = [&](std::size_t sensor) { sims[sensor].sim->set_object("coin"); };
    Rig rig(context, cfg, sensors);
    rig.start();

    std::vector<ImageD> backgrounds;  // what each sensor's D must be measured against
    for (std::size_t i = 0; i < 3; ++i) {
        for (const ImageD& m : means[i]) ASSERT_FALSE(m.data.empty()) << "no background frames for sensor " << i;
        backgrounds.push_back(fuse_reference(means[i], cfg.fusion));
    }
    // The backgrounds really differ: a D against the wrong sensor's is far off.
    for (std::size_t i = 1; i < 3; ++i)
        ASSERT_GT(max_abs_diff(backgrounds[i], backgrounds[0]), 0.1) << "sensor " << i << "'s background";

    for (int c = 0; c < 2; ++c) {
        const CycleResult r = rig.next();
        ASSERT_EQ(r.sensors.size(), 3u);
        for (std::size_t i = 0; i < 3; ++i) {
            const SensorCycle& s = r.sensors[i];
            SCOPED_TRACE(s.serial + " cycle " + std::to_string(c));
            ASSERT_EQ(s.status, SensorStatus::Ok) << s.error;
            ASSERT_TRUE(s.fused);
            ASSERT_TRUE(s.metrics.background_diff);
            const double want = mean_abs_difference(*s.fused, backgrounds[i]);
            EXPECT_NEAR(*s.metrics.background_diff, want, 1e-4 * want);
            for (std::size_t j = 0; j < 3; ++j) {
                if (j == i) continue;
                const double wrong = mean_abs_difference(*s.fused, backgrounds[j]);
                EXPECT_GT(std::abs(wrong - want), 0.01 * want) << "sensor " << j << "'s background is no different";
            }
        }
    }
}

class VulkanRigBackground : public VulkanTest {};

TEST_F(VulkanRigBackground, EachSensorMeasuredAgainstItsOwnBackground) { check_backgrounds(&ctx()); }

// The same wiring on the CPU path (no Vulkan context).
TEST(RigBackgroundCpu, EachSensorMeasuredAgainstItsOwnBackground) { check_backgrounds(nullptr); }

}  // namespace
}  // namespace vkfuse::test

// Recording a rig run and replaying the dataset reproduces the run's fused
// frames and metrics bit for bit, with one cycle in flight or two.
#include <gtest/gtest.h>

#include <cstring>

#include "rig_support.hpp"
#include "temp_dir.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::test {
namespace {

struct Outcome {
    std::vector<Image> fused;  // cycle-major, sensor-minor
    std::vector<Metrics> metrics;
};

RigConfig replayable_config() {
    RigConfig cfg;
    cfg.sequence = parse_sequence("15,15,15+0,15,0+15,15,15");  // a setting twice: replay keeps their order
    cfg.fusion.method = Method::Laplacian;
    cfg.background_frames = 3;
    return cfg;
}

Outcome run_cycles(Rig& rig, int cycles, DatasetWriter* recorder, const RigConfig& cfg) {
    Outcome out;
    rig.start();
    for (int c = 0; c < cycles; ++c) {
        const CycleResult r = rig.next();
        for (std::size_t i = 0; i < r.sensors.size(); ++i) {
            const SensorCycle& s = r.sensors[i];
            EXPECT_EQ(s.status, SensorStatus::Ok) << s.error;
            out.fused.push_back(*s.fused);
            out.metrics.push_back(s.metrics);
            if (recorder)
                for (std::size_t k = 0; k < s.frames.size(); ++k)
                    recorder->add_frame(int(i), "coin", false, s.frames[k], cfg.sequence[k], std::int64_t(c));
        }
    }
    return out;
}

class VulkanRigReplay : public VulkanTest {};

TEST_F(VulkanRigReplay, ReproducesTheRecordedRunBitForBitOneOrTwoCyclesInFlight) {
    TempDir tmp;
    const std::string dir = tmp.file("run");
    constexpr int kCycles = 4;
    Outcome live;
    {
        std::vector<SimRigSensor> sims{sim_sensor(1, 0.05, "nothing"), sim_sensor(2, 0.05, "nothing")};
        DatasetWriter recorder(dir, "test");
        RigConfig cfg = replayable_config();
        cfg.on_background = [&](std::size_t i, const Illumination& setting, const std::vector<Frame>& frames) {
            for (const Frame& f : frames) recorder.add_frame(int(i), "nothing", true, f, setting);
        };
        cfg.after_background = [&](std::size_t i) { sims[i].sim->set_object("coin"); };
        std::vector<RigSensor> sensors;
        for (const SimRigSensor& s : sims) {
            recorder.add_sensor(s.sim->info());
            sensors.push_back({s.sim, s.clock});
        }
        recorder.set_run({cfg.sequence, cfg.fusion, cfg.background_frames});
        Rig rig(&ctx(), cfg, sensors);
        live = run_cycles(rig, kCycles, &recorder, cfg);
        recorder.finish();
    }
    auto dataset = std::make_shared<const Dataset>(read_dataset(dir));
    // Replayed as a round trip per cycle, then with two cycles in flight
    // (the device fuses cycle c + 1 while c is returned): the same results,
    // in the same order.
    for (int in_flight : {1, 2}) {
        SCOPED_TRACE(std::to_string(in_flight) + " cycle(s) in flight");
        RigConfig cfg = replayable_config();
        cfg.judging = FrameJudging::Label;
        cfg.cycles_in_flight = in_flight;
        std::vector<RigSensor> sensors;
        for (const DatasetSensorRecord& s : dataset->sensors)
            sensors.push_back({std::make_shared<DatasetSensor>(dataset, s.info.serial, "coin"), nullptr});
        Rig replay(&ctx(), cfg, sensors);
        const Outcome again = run_cycles(replay, kCycles, nullptr, cfg);
        ASSERT_EQ(again.fused.size(), live.fused.size());
        for (std::size_t i = 0; i < live.fused.size(); ++i) {
            ASSERT_TRUE(live.fused[i].same_shape(again.fused[i]));
            EXPECT_EQ(std::memcmp(live.fused[i].data.data(), again.fused[i].data.data(),
                                  live.fused[i].size() * sizeof(float)),
                      0)
                << "sensor-cycle " << i;
            EXPECT_EQ(live.metrics[i].sharpness, again.metrics[i].sharpness);
            EXPECT_EQ(live.metrics[i].contrast, again.metrics[i].contrast);
            EXPECT_EQ(live.metrics[i].background_diff, again.metrics[i].background_diff);
        }
    }
}

TEST_F(VulkanRigReplay, TwoCyclesInFlightNeedAGpuAndSkipOff) {
    RigConfig cfg = replayable_config();
    cfg.cycles_in_flight = 2;
    const std::vector<RigSensor> sensors{{sim_sensor(1, 0.05).sim, nullptr}};
    try {
        Rig rig(nullptr, cfg, sensors);
        ADD_FAILURE() << "a CPU rig took 2 cycles in flight";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("need a GPU context"), std::string::npos) << e.what();
    }
    cfg.skip.policy = SkipPolicy::Idle;
    try {
        Rig rig(&ctx(), cfg, sensors);
        ADD_FAILURE() << "a skipping rig took 2 cycles in flight";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("need skip off"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace vkfuse::test

// A sensor that throws or stalls never stops the others: its serial is in the
// error, the plan still runs once per cycle for everyone.
#include <gtest/gtest.h>

#include "expect_error.hpp"
#include "rig_support.hpp"
#include "vk_fixture.hpp"

namespace vkfuse::test {
namespace {

class VulkanRigFailure : public VulkanTest {};

constexpr int kAfterCalibration = 120;  // grabs: calibration and background take about 90

RigConfig two_settings(double timeout_s) {
    RigConfig cfg;
    cfg.sequence = parse_sequence("15,15,15+0,15,0");
    cfg.fusion.method = Method::Brovey;
    cfg.background_frames = 1;
    cfg.cycle_timeout_s = timeout_s;
    return cfg;
}

TEST_F(VulkanRigFailure, ThrowingAndStallingSensorsDoNotStopTheOthers) {
    auto good = sim_sensor(1, 0.03), throwing = sim_sensor(2, 0.03), stalling = sim_sensor(3, 0.03);
    auto thrower = std::make_shared<FaultySensor>(throwing.logged, FaultySensor::Fault::Throw, kAfterCalibration);
    auto staller = std::make_shared<FaultySensor>(stalling.logged, FaultySensor::Fault::Stall, kAfterCalibration);
    constexpr double kTimeout = 2.0;
    Rig rig(&ctx(), two_settings(kTimeout),
            {{good.logged, good.clock}, {thrower, throwing.clock}, {staller, stalling.clock}});
    rig.start();
    bool saw_failed = false, saw_timeout = false;
    constexpr int kCycles = 30;
    for (int c = 0; c < kCycles; ++c) {
        const CycleResult r = rig.next();
        ASSERT_EQ(r.sensors[0].status, SensorStatus::Ok) << "cycle " << c << ": " << r.sensors[0].error;
        const SensorCycle& failed = r.sensors[1];
        if (failed.status == SensorStatus::Failed) {
            saw_failed = true;
            EXPECT_EQ(failed.error, "SIM-0002: USB transfer failed (test fault)");
            EXPECT_TRUE(failed.frames.empty());
        }
        const SensorCycle& late = r.sensors[2];
        if (late.status == SensorStatus::Timeout) {
            // The first timeout costs one wait; after that the rig stops waiting for it.
            if (saw_timeout) {
                EXPECT_LT(r.capture_wait_s, kTimeout / 2) << "cycle " << c;
            }
            saw_timeout = true;
            EXPECT_EQ(late.error.rfind("SIM-0003: no frames within", 0), 0u) << late.error;
        }
        EXPECT_EQ(rig.submits(), std::uint64_t(c + 1));
    }
    EXPECT_TRUE(saw_failed);
    EXPECT_TRUE(saw_timeout);
    EXPECT_TRUE(staller->stalled());
    EXPECT_FALSE(rig.all_failed());
    staller->release();
}

TEST_F(VulkanRigFailure, AnUnpluggedSensorFailsWhileGoneAndRejoinsWhenBack) {
    auto good = sim_sensor(1, 0.03), other = sim_sensor(2, 0.03);
    auto cable = std::make_shared<UnpluggableSensor>(other.logged);
    Rig rig(&ctx(), two_settings(2.0), {{good.logged, good.clock}, {cable, other.clock}});
    rig.start();
    enum class Phase { Before, Gone, Back } phase = Phase::Before;
    int failed_cycles = 0, ok_after = 0;
    for (int c = 0; c < 200 && ok_after < 3; ++c) {
        const CycleResult r = rig.next();
        ASSERT_EQ(r.sensors[0].status, SensorStatus::Ok) << "cycle " << c << ": " << r.sensors[0].error;
        const SensorCycle& s = r.sensors[1];
        if (phase == Phase::Before) {
            ASSERT_EQ(s.status, SensorStatus::Ok) << s.error;
            if (c == 2) {
                cable->unplug();
                phase = Phase::Gone;
            }
        } else if (phase == Phase::Gone) {
            if (s.status == SensorStatus::Failed) {
                EXPECT_EQ(s.error, "SIM-0002: unplugged (test)");
                EXPECT_TRUE(s.frames.empty());
                if (++failed_cycles == 3) {
                    cable->replug();
                    phase = Phase::Back;
                }
            }
        } else if (s.status == SensorStatus::Ok) {
            ++ok_after;
            EXPECT_EQ(s.frames.size(), 2u);
        }
        EXPECT_EQ(rig.submits(), std::uint64_t(c + 1));
    }
    EXPECT_EQ(failed_cycles, 3);
    EXPECT_GT(cable->refused(), 0);
    EXPECT_EQ(ok_after, 3) << "the replugged sensor never rejoined";
    EXPECT_FALSE(rig.all_failed());
}

// With every sensor gone nothing can deliver, but one may come back: each
// cycle waits out its timeout for that (a fusion host whose capture host
// went away, a hand whose hub was unplugged) instead of returning at once,
// over and over, fusing nothing at full speed.
TEST_F(VulkanRigFailure, EverySensorUnpluggedMakesCyclesWaitRatherThanSpin) {
    auto only = sim_sensor(1, 0.03);
    auto cable = std::make_shared<UnpluggableSensor>(only.logged);
    constexpr double kTimeout = 0.3;
    Rig rig(&ctx(), two_settings(kTimeout), {{cable, only.clock}});
    rig.start();
    ASSERT_EQ(rig.next().sensors[0].status, SensorStatus::Ok);
    cable->unplug();
    int gone = 0;
    for (int c = 0; c < 100 && gone < 4; ++c) {
        const CycleResult r = rig.next();
        if (r.sensors[0].status != SensorStatus::Failed) continue;
        ++gone;
        EXPECT_GE(r.capture_wait_s, 0.9 * kTimeout) << "cycle " << r.cycle << " of no sensor did not wait";
    }
    EXPECT_EQ(gone, 4);
    cable->replug();
    bool back = false;
    for (int c = 0; c < 100 && !back; ++c) back = rig.next().sensors[0].status == SensorStatus::Ok;
    EXPECT_TRUE(back) << "the replugged sensor never rejoined";
}

TEST_F(VulkanRigFailure, SensorFailingAtStartupIsReportedEveryCycle) {
    auto good = sim_sensor(1, 0.0), bad = sim_sensor(2, 0.0);
    auto dead = std::make_shared<FaultySensor>(bad.logged, FaultySensor::Fault::Throw, 0);
    Rig rig(&ctx(), two_settings(2.0), {{dead, bad.clock}, {good.logged, good.clock}});
    rig.start();
    for (int c = 0; c < 3; ++c) {
        const CycleResult r = rig.next();
        EXPECT_EQ(r.sensors[0].status, SensorStatus::Failed);
        EXPECT_EQ(r.sensors[0].serial, "SIM-0002");
        EXPECT_EQ(r.sensors[1].status, SensorStatus::Ok);
    }
}

TEST_F(VulkanRigFailure, NoSensorStartingIsAnError) {
    auto bad = sim_sensor(7, 0.0);
    auto dead = std::make_shared<FaultySensor>(bad.logged, FaultySensor::Fault::Throw, 0);
    Rig rig(&ctx(), two_settings(1.0), {{dead, bad.clock}});
    expect_error([&] { rig.start(); }, "SIM-0007", ErrorKind::Device, "USB transfer failed");
}

TEST_F(VulkanRigFailure, SensorsOfDifferentSizesAreRefused) {
    auto qvga = sim_sensor(1, 0.0);
    SimDigitOptions o;
    o.vga = true;
    o.serial = "SIM-0002";
    auto vga = std::make_shared<SimDigit>(o);
    expect_error(
        [&] {
            Rig(&ctx(), two_settings(1.0), {{qvga.logged, qvga.clock}, {vga, nullptr}});
        },
        "SIM-0002", ErrorKind::Shape, "differ from SIM-0001");
}

}  // namespace
}  // namespace vkfuse::test

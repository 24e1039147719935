// Sensors of one origin (another host's rig, Frame::origin) are fused in
// step: when one sensor's cycle was lost on the way, it sits that cycle out,
// and the others are neither fused beside its next cycle nor left a cycle
// behind it for the rest of the run.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "vk_fixture.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::test {
namespace {

class VulkanRigOrigin : public VulkanTest {};

constexpr int kSize = 16;
constexpr std::uint64_t kOrigin = 7;

// Labelled frames, as a fusion host's remote sensor hands them out: the
// background (one frame per setting asked for), then the scripted origin
// cycles, K frames each. Every pixel of a cycle's frame k is 10 * cycle + k,
// so a fused cycle's frames say which cycle they came from.
class OriginSensor : public Sensor {
public:
    OriginSensor(std::string serial, IlluminationSequence sequence, std::vector<std::uint64_t> cycles)
        : serial_(std::move(serial)), sequence_(std::move(sequence)), cycles_(std::move(cycles)) {}

    SensorInfo info() const override {
        SensorInfo i;
        i.model = "origin test";
        i.serial = serial_;
        i.width = kSize;
        i.height = kSize;
        i.fps = 30;
        i.leds = LedLayout::digit();
        return i;
    }
    void set_illumination(const Illumination& s) override { requested_ = s; }
    Frame grab() override {
        if (background_left_ > 0) {
            --background_left_;
            return frame(requested_, 200, std::nullopt);
        }
        if (next_ >= cycles_.size() * sequence_.size()) {
            // Silent from here on, as a remote sensor whose host went quiet.
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
            throw Error(ErrorKind::Timeout, serial_ + ": script ended (test)");
        }
        const std::size_t c = next_ / sequence_.size(), k = next_ % sequence_.size();
        ++next_;
        return frame(sequence_[k], std::uint8_t(10 * cycles_[c] + k), cycles_[c]);
    }

private:
    Frame frame(const Illumination& lit, std::uint8_t value, std::optional<std::uint64_t> cycle) {
        Frame f;
        f.index = index_++;
        f.timestamp = double(f.index) / 30;
        f.height = f.width = kSize;
        f.pixels.assign(std::size_t(kSize) * kSize * 3, value);
        f.illumination = lit;
        if (cycle) {
            f.origin = kOrigin;
            f.origin_cycle = *cycle;
        }
        return f;
    }
    std::string serial_;
    IlluminationSequence sequence_;
    std::vector<std::uint64_t> cycles_;
    Illumination requested_;
    int background_left_ = 2;  // background_frames 1, two settings
    std::size_t next_ = 0;
    std::uint64_t index_ = 0;
};

TEST_F(VulkanRigOrigin, ASensorWhoseCycleWasLostSitsItOutAndTheOthersStayInStep) {
    RigConfig cfg;
    cfg.sequence = parse_sequence("15,15,15+0,15,0");
    cfg.fusion.method = Method::Brovey;
    cfg.background_frames = 1;
    cfg.judging = FrameJudging::Label;
    cfg.skip.policy = SkipPolicy::Off;
    cfg.cycle_timeout_s = 5;
    const std::vector<std::uint64_t> whole{0, 1, 2, 3, 4, 5}, lost_2{0, 1, 3, 4, 5};
    Rig rig(&ctx(), cfg,
            {{std::make_shared<OriginSensor>("ORIGIN-A", cfg.sequence, whole), nullptr},
             {std::make_shared<OriginSensor>("ORIGIN-B", cfg.sequence, lost_2), nullptr},
             {std::make_shared<OriginSensor>("ORIGIN-C", cfg.sequence, whole), nullptr}});
    rig.start();
    for (std::uint64_t c = 0; c < whole.size(); ++c) {
        const CycleResult r = rig.next();
        for (const SensorCycle& s : r.sensors) {
            if (s.serial == "ORIGIN-B" && c == 2) {
                EXPECT_EQ(s.status, SensorStatus::Timeout) << "rig cycle 2 fused B's cycle 3";
                EXPECT_EQ(s.error, "ORIGIN-B: no frames of its origin's cycle 2 (its next are of cycle 3)");
                continue;
            }
            ASSERT_EQ(s.status, SensorStatus::Ok) << "rig cycle " << c << ": " << s.error;
            ASSERT_EQ(s.frames.size(), 2u);
            for (std::size_t k = 0; k < 2; ++k) {
                EXPECT_EQ(s.frames[k].origin_cycle, c) << s.serial << " in rig cycle " << c;
                EXPECT_EQ(s.frames[k].pixels.front(), std::uint8_t(10 * c + k)) << s.serial << " in rig cycle " << c;
            }
        }
    }
}

}  // namespace
}  // namespace vkfuse::test

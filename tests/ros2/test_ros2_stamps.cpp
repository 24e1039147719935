// What a published cycle is dated: header.stamp of a sensor's fused image,
// metrics and cycle is its newest frame's capture time (when the cycle was
// complete, as metrics.jsonl's "timestamp"), whatever the frames' order, and
// each frame of the cycle keeps its own. The publisher is given a capture
// time that maps a sensor's clock straight onto the epoch, so every stamp is
// known exactly; Cyclone readers of the topics check them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "ros2/dds_entities.hpp"
#include "ros2/messages.hpp"
#include "sensor_msgs.h"
#include "vkfuse/ros2/publisher.hpp"

namespace vkfuse::test {
namespace {

using namespace vkfuse::ros2;

constexpr int kWidth = 8, kHeight = 6;

int own_domain() { return 10 + int((getpid() + 131) % 220); }

std::int64_t nanoseconds(const builtin_interfaces_msg_dds__Time_& t) {
    return std::int64_t(t.sec) * 1'000'000'000 + std::int64_t(t.nanosec);
}

// The sample a reader holds, once it came (within 10 s); its stamp.
template <class Message>
std::int64_t stamp_taken(const DdsEntity& participant, const DdsEntity& reader,
                         std::int64_t (*stamp)(const Message&)) {
    const DataWait arrived(participant, reader);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
        LoanedSample<Message> sample(reader);
        if (sample.valid()) return stamp(sample.message());
        arrived.wait(std::chrono::milliseconds(100));
    }
    ADD_FAILURE() << "no sample within 10 s";
    return -1;
}

TEST(Ros2Stamps, ACycleIsDatedByItsNewestFrameAndEachFrameByItsOwn) {
    const int domain = own_domain();
    SensorInfo info;
    info.serial = "STAMP-1";
    info.width = kWidth;
    info.height = kHeight;
    const IlluminationSequence sequence = {Illumination({15, 15, 15}), Illumination({0, 15, 0})};
    RigTopics topics{{info}, sequence, FusionSpec{}, MetricSet{Metric::Sharpness}, SkipConfig{}, 2, true};
    // Sensor clock t is t seconds after the epoch.
    CaptureTime epoch_plus = [](std::size_t, double t) {
        return std::chrono::system_clock::time_point(
            std::chrono::duration_cast<std::chrono::system_clock::duration>(std::chrono::duration<double>(t)));
    };
    RigPublisher publisher(topics, PublisherOptions{domain, ImageEncoding::Rgb8, true}, epoch_plus);

    DdsEntity participant = make_participant(domain);
    const TopicQos qos = TopicQos::reader(4);
    DdsEntity fused = make_reader(participant, sensor_msgs_msg_dds__Image__desc, "/vkfuse/STAMP_1/fused", qos);
    DdsEntity metrics =
        make_reader(participant, vkfuse_msgs_msg_dds__FusionMetrics__desc, "/vkfuse/STAMP_1/metrics", qos);
    DdsEntity cycle = make_reader(participant, vkfuse_msgs_msg_dds__LitCycle__desc, "/vkfuse/STAMP_1/cycle", qos);
    DdsEntity background =
        make_reader(participant, vkfuse_msgs_msg_dds__Background__desc, "/vkfuse/STAMP_1/background", qos);

    // Matched first: a volatile topic keeps nothing for a reader still to come.
    const auto matched_by = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!publisher.has_subscribers(0) && std::chrono::steady_clock::now() < matched_by)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_TRUE(publisher.has_subscribers(0));

    const Image image(kHeight, kWidth, 3);
    // A cycle of frames taken at these times (sensor clock), lit in the sequence's order.
    auto cycle_taken = [&](std::uint64_t number, const std::vector<double>& taken) {
        CycleResult result;
        result.cycle = number;
        SensorCycle& s = result.sensors.emplace_back();
        s.serial = info.serial;
        for (std::size_t k = 0; k < taken.size(); ++k) {
            Frame f;
            f.index = k;
            f.timestamp = taken[k];
            f.height = kHeight;
            f.width = kWidth;
            f.illumination = sequence[k];
            f.pixels.assign(std::size_t(kWidth * kHeight * 3), std::uint8_t(40 * k));
            s.frames.push_back(f);
        }
        s.fused = &image;
        s.metrics.sharpness = 0.5;
        return result;
    };
    publisher.publish(cycle_taken(7, {100.25, 100.75}));

    const std::int64_t newest = 100'750'000'000;
    EXPECT_EQ(stamp_taken<sensor_msgs_msg_dds__Image_>(participant, fused,
                                                       [](const auto& m) { return nanoseconds(m.header.stamp); }),
              newest);
    EXPECT_EQ(stamp_taken<vkfuse_msgs_msg_dds__FusionMetrics_>(
                  participant, metrics, [](const auto& m) { return nanoseconds(m.header.stamp); }),
              newest);
    EXPECT_EQ(stamp_taken<vkfuse_msgs_msg_dds__LitCycle_>(participant, cycle,
                                                          [](const auto& m) { return nanoseconds(m.header.stamp); }),
              newest);
    // A sliding window's order (the frame of setting 0 the newer one): the
    // cycle is dated by its newest frame still, each frame by its own.
    const DataWait again(participant, cycle);
    publisher.publish(cycle_taken(8, {101.75, 101.25}));
    for (int tries = 0; tries < 100; ++tries) {
        LoanedSample<vkfuse_msgs_msg_dds__LitCycle_> sample(cycle);
        if (!sample.valid()) {
            again.wait(std::chrono::milliseconds(100));
            continue;
        }
        ASSERT_EQ(sample.message().frames._length, 2u);
        EXPECT_EQ(nanoseconds(sample.message().header.stamp), 101'750'000'000);
        EXPECT_EQ(nanoseconds(sample.message().frames._buffer[0].image.header.stamp), 101'750'000'000);
        EXPECT_EQ(nanoseconds(sample.message().frames._buffer[1].image.header.stamp), 101'250'000'000);
        return;
    }
    FAIL() << "the second cycle never came";
}

}  // namespace
}  // namespace vkfuse::test

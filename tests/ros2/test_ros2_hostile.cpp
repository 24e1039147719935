// What a fusion host hears is input from the network: a test publisher
// (Cyclone DDS, the C types vkfuse's own messages compile to) describes a
// sensor and then sends it every kind of bad sample among good ones. The
// remote sensor hands out only the good cycles, whole and in order, counts
// each bad one, says so in a line, and never crashes; a background that
// never comes ends the sensor's start with one line; one taken is not
// listened for again.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "ros2/dds_entities.hpp"
#include "ros2/messages.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"
#include "vkfuse/ros2/remote.hpp"

namespace vkfuse::test {
namespace {

using namespace vkfuse::ros2;

constexpr int kWidth = 8, kHeight = 6;
const std::string kSerial = "HOST-1";
const IlluminationSequence kSequence = {Illumination({15, 15, 15}), Illumination({0, 15, 0})};

int own_domain() { return 10 + int((getpid() + 7) % 220); }

Frame frame_of(std::uint64_t index, std::uint8_t value) {
    Frame f;
    f.index = index;
    f.timestamp = double(index) / 60;
    f.height = kHeight;
    f.width = kWidth;
    f.pixels.assign(std::size_t(kWidth * kHeight * 3), value);
    return f;
}

// A capture host of one sensor that writes whatever the test makes of its messages.
struct TestPublisher {
    DdsEntity participant;
    DdsEntity rig, cycle, background;
    LedSettings settings{kSequence};

    explicit TestPublisher(int domain)
        : participant(dds_create_participant(dds_domainid_t(domain), nullptr, nullptr), "participant") {
        const TopicQos latched(16, true);
        rig = make_writer(participant, vkfuse_msgs_msg_dds__RigDescription__desc, "/vkfuse/rig", latched);
        cycle = make_writer(participant, vkfuse_msgs_msg_dds__LitCycle__desc, "/vkfuse/HOST_1/cycle", latched);
        background = make_writer(participant, vkfuse_msgs_msg_dds__Background__desc, "/vkfuse/HOST_1/background", latched);
    }

    void describe() {
        std::vector<std::string> channels{"r", "g", "b"};
        std::vector<char*> names;
        for (std::string& c : channels) names.push_back(text(c));
        const std::string serial = kSerial, token = "HOST_1", model = "DIGIT", method = "none", skip = "off";
        std::vector<vkfuse_msgs_msg_dds__SensorDescription_> sensors{
            {text(serial), text(token), text(model), 60.0, kWidth, kHeight, text(model),
             sequence_of<dds_sequence_string>(names), 15}};
        std::vector<char*> metrics;
        vkfuse_msgs_msg_dds__RigDescription_ msg{};
        msg.header = {stamp_of(std::chrono::system_clock::now()), text(serial)};
        msg.sensors = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__SensorDescription_>(sensors);
        msg.settings = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__LedSetting_>(settings.messages);
        msg.method = text(method);
        msg.metrics = sequence_of<dds_sequence_string>(metrics);
        msg.skip = text(skip);
        msg.background_frames = 2;
        msg.frames = true;
        ASSERT_EQ(dds_write(rig.get(), &msg), DDS_RETCODE_OK);
    }

    // frames lit by settings[k] (the sequence's unless told), as LitCycle
    // `number`; `edit` spoils the message before it goes.
    template <class Edit>
    void send_cycle(std::uint64_t number, const std::vector<Frame>& frames, Edit edit,
                    const DdsEntity* writer = nullptr, std::string serial = kSerial) {
        const auto stamp = stamp_of(std::chrono::system_clock::now());
        LitFrames messages(serial);
        for (std::size_t k = 0; k < frames.size(); ++k)
            messages.add(frames[k], stamp, settings.messages[k % settings.messages.size()]);
        vkfuse_msgs_msg_dds__LitCycle_ msg{};
        msg.header = {stamp, text(serial)};
        msg.serial = text(serial);
        msg.cycle = number;
        msg.frames = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__LitFrame_>(messages.messages);
        edit(msg);
        ASSERT_EQ(dds_write((writer ? *writer : cycle).get(), &msg), DDS_RETCODE_OK);
    }
    void send_cycle(std::uint64_t number, const std::vector<Frame>& frames) {
        send_cycle(number, frames, [](auto&) {});
    }

    void send_background() {
        std::vector<Frame> frames{frame_of(0, 10), frame_of(1, 11), frame_of(2, 20), frame_of(3, 21)};
        const auto stamp = stamp_of(std::chrono::system_clock::now());
        LitFrames messages(kSerial);
        for (std::size_t j = 0; j < frames.size(); ++j) messages.add(frames[j], stamp, settings.messages[j / 2]);
        vkfuse_msgs_msg_dds__Background_ msg{};
        msg.header = {stamp, text(kSerial)};
        msg.serial = text(kSerial);
        msg.frames_per_setting = 2;
        msg.frames = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__LitFrame_>(messages.messages);
        ASSERT_EQ(dds_write(background.get(), &msg), DDS_RETCODE_OK);
    }
};

std::vector<Frame> cycle_frames(std::uint64_t number) {
    return {frame_of(10 + 2 * number, std::uint8_t(100 + number)), frame_of(11 + 2 * number, std::uint8_t(150 + number))};
}

// The next whole cycle the sensor hands out, as the rig's labelled switcher takes it.
std::vector<Frame> grab_cycle(Sensor& sensor) {
    std::vector<Frame> out;
    for (const Illumination& s : kSequence) {
        sensor.set_illumination(s);
        out.push_back(sensor.grab());
    }
    return out;
}

// A fusion host of the test publisher's sensor, reporting nothing.
RemoteRigOptions options_for(int domain, double startup_timeout_s) {
    RemoteRigOptions options;
    options.domain = domain;
    options.serials = {kSerial};
    options.startup_timeout_s = startup_timeout_s;
    options.report = [](const std::string&) {};
    return options;
}

TEST(Ros2Hostile, BadSamplesAreRefusedCountedAndNeverHandedOut) {
    const int domain = own_domain();
    TestPublisher host(domain);
    host.describe();
    host.send_background();
    std::vector<std::string> lines;
    std::mutex lines_mutex;
    RemoteRigOptions options = options_for(domain, 30);
    options.queue_cycles = 32;  // every sample sent is still there when the sensor is asked
    options.report = [&](const std::string& line) {
        std::lock_guard lock(lines_mutex);
        lines.push_back(line);
    };
    RemoteRig rig(options);
    ASSERT_EQ(rig.description().sensors.size(), 1u);
    EXPECT_EQ(rig.description().sequence, kSequence);
    Sensor& sensor = *rig.sensors().front().sensor;
    // The background first, each setting's frames under it.
    for (const auto& [setting, values] : {std::pair{kSequence[0], std::vector<int>{10, 11}}, {kSequence[1], {20, 21}}})
        for (int v : values) {
            sensor.set_illumination(setting);
            const Frame f = sensor.grab();
            EXPECT_EQ(f.pixels.front(), v);
            EXPECT_EQ(f.illumination, setting);
        }

    int bad = 0;
    host.send_cycle(0, cycle_frames(0));
    // One bad sample of each kind, then a good one.
    host.send_cycle(1, {cycle_frames(1)[0]});  // one frame of two
    ++bad;
    host.send_cycle(1, cycle_frames(1), [](auto& m) { m.frames._buffer[1].image.width = kWidth + 1; });  // size
    ++bad;
    host.send_cycle(1, cycle_frames(1), [](auto& m) { m.frames._buffer[0].image.data._length -= 3; });  // short data
    ++bad;
    host.send_cycle(1, cycle_frames(1), [](auto& m) { m.frames._buffer[0].image.step += 1; });  // step
    ++bad;
    static std::string bgr8 = "bgr8";
    host.send_cycle(1, cycle_frames(1), [](auto& m) { m.frames._buffer[0].image.encoding = text(bgr8); });  // encoding
    ++bad;
    host.send_cycle(1, cycle_frames(1), [&](auto& m) { m.frames._buffer[0].setting = host.settings.messages[1]; });
    ++bad;  // a frame lit by the other setting
    static std::vector<std::uint8_t> too_bright{16, 0, 0};
    host.send_cycle(1, cycle_frames(1), [](auto& m) {
        m.frames._buffer[1].setting.levels = sequence_of<dds_sequence_uint8>(too_bright);
    });
    ++bad;  // a level over the layout's 15
    host.send_cycle(1, cycle_frames(1), [](auto&) {}, nullptr, "HOST-2");  // another serial on this topic
    ++bad;
    host.send_cycle(2, cycle_frames(2));
    host.send_cycle(1, cycle_frames(1));  // going backwards
    ++bad;
    {
        // A second publisher claiming the serial while the first is alive.
        TestPublisher impostor(domain);
        host.send_cycle(3, cycle_frames(3));
        std::this_thread::sleep_for(std::chrono::milliseconds(300));  // both matched
        impostor.send_cycle(4, cycle_frames(40));
        ++bad;
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        host.send_cycle(5, cycle_frames(5));
        // Only the good cycles, whole and in order.
        for (std::uint64_t n : {0, 2, 3, 5}) {
            const std::vector<Frame> got = grab_cycle(sensor);
            const std::vector<Frame> sent = cycle_frames(n);
            ASSERT_EQ(got.size(), 2u);
            for (std::size_t k = 0; k < 2; ++k) {
                EXPECT_EQ(got[k].pixels, sent[k].pixels) << "cycle " << n << ", frame " << k;
                EXPECT_EQ(got[k].index, sent[k].index);
                EXPECT_EQ(got[k].illumination, kSequence[k]);
            }
        }
    }
    const RemoteCounts counts = rig.counts(0);
    EXPECT_EQ(counts.malformed, std::uint64_t(bad));
    EXPECT_EQ(counts.cycles, 4u);
    EXPECT_EQ(counts.missed, 2u);  // cycles 1 and 4 of the capture host never arrived whole
    std::lock_guard lock(lines_mutex);
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines.front().rfind(kSerial + ": ", 0), 0u) << lines.front();
}

// A fusion host takes a sensor's background once. Its reader goes with the
// background, so a capture host that restarts (and latches its background
// again, megabytes a sensor) sends it to no one on this host.
TEST(Ros2Hostile, TheBackgroundIsReadOnceAndItsReaderThenGoes) {
    const int domain = own_domain();
    TestPublisher host(domain);
    host.describe();
    host.send_background();
    RemoteRig rig(options_for(domain, 30));
    Sensor& sensor = *rig.sensors().front().sensor;
    auto readers_of_background = [&] {
        dds_publication_matched_status_t status{};
        EXPECT_EQ(dds_get_publication_matched_status(host.background.get(), &status), DDS_RETCODE_OK);
        return status.current_count;
    };
    for (const Illumination& setting : kSequence)
        for (int j = 0; j < 2; ++j) {
            sensor.set_illumination(setting);
            sensor.grab();
        }
    EXPECT_EQ(readers_of_background(), 1u);  // the sensor's, until its first cycle
    host.send_cycle(0, cycle_frames(0));
    EXPECT_EQ(grab_cycle(sensor).size(), 2u);
    // Unmatching travels through discovery: a busy host takes a moment.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (readers_of_background() != 0 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(readers_of_background(), 0u);
    host.send_cycle(1, cycle_frames(1));
    EXPECT_EQ(grab_cycle(sensor).front().pixels, cycle_frames(1).front().pixels);  // cycles still come
}

TEST(Ros2Hostile, ABackgroundThatNeverComesEndsTheStartWithOneLine) {
    const int domain = own_domain();
    TestPublisher host(domain);
    host.describe();  // and no background
    RemoteRig rig(options_for(domain, 1));
    Sensor& sensor = *rig.sensors().front().sensor;
    sensor.set_illumination(kSequence[0]);
    try {
        sensor.grab();
        FAIL() << "a background frame out of nothing";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Timeout);
        EXPECT_EQ(std::string(e.what()),
                  "HOST-1: no background from its capture host within 1 s (/vkfuse/HOST_1/background)");
    }
}

TEST(Ros2Hostile, NoCaptureHostIsOneLine) {
    RemoteRigOptions options;
    options.domain = own_domain();
    options.serials = {"NOBODY-1"};
    options.startup_timeout_s = 0.5;
    try {
        RemoteRig rig(options);
        FAIL() << "a sensor out of nothing";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Timeout);
        EXPECT_EQ(std::string(e.what()), "--source ros2: no capture host describes NOBODY-1 in ROS domain " +
                                             std::to_string(options.domain) + " within 0.5 s");
    }
}

}  // namespace
}  // namespace vkfuse::test

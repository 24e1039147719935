// ros2/messages.hpp - building the C types idlc generates for ROS 2's
// messages: times, strings, sequences, LED settings and lit frames (read
// back, and checked, in ros2/remote_checks.hpp).
#pragma once
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "sensor_msgs.h"
#include "vkfuse/sensor/illumination.hpp"
#include "vkfuse/sensor/sensor.hpp"
#include "vkfuse_msgs.h"

namespace vkfuse::ros2 {

builtin_interfaces_msg_dds__Time_ stamp_of(std::chrono::system_clock::time_point t);

// DDS's C types take char*; dds_write only reads through it.
inline char* text(const std::string& s) { return const_cast<char*>(s.c_str()); }

// A sequence pointing at items (which must outlive the message).
template <class Sequence, class T>
Sequence sequence_of(std::vector<T>& items) {
    Sequence s{};
    s._maximum = s._length = std::uint32_t(items.size());
    s._buffer = items.empty() ? nullptr : items.data();
    s._release = false;
    return s;
}

// A setting's levels as LedSetting's, and the messages pointing at them.
struct LedSettings {
    std::vector<std::vector<std::uint8_t>> levels;
    std::vector<vkfuse_msgs_msg_dds__LedSetting_> messages;

    explicit LedSettings(const IlluminationSequence& sequence);
    LedSettings(const LedSettings&) = delete;
    LedSettings& operator=(const LedSettings&) = delete;
};

// Frames of one sensor as LitFrame messages pointing into them (rgb8, the
// frames' own bytes; no copy).
struct LitFrames {
    std::vector<vkfuse_msgs_msg_dds__LitFrame_> messages;

    explicit LitFrames(const std::string& serial) : serial_(serial) {}
    // frame (which, with the serial and setting's levels, outlives this)
    // exposed at stamp under setting.
    void add(const Frame& frame, const builtin_interfaces_msg_dds__Time_& stamp,
             const vkfuse_msgs_msg_dds__LedSetting_& setting);

private:
    const std::string& serial_;
};

}  // namespace vkfuse::ros2

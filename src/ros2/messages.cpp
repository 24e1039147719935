#include "ros2/messages.hpp"

namespace vkfuse::ros2 {

builtin_interfaces_msg_dds__Time_ stamp_of(std::chrono::system_clock::time_point t) {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
    const auto sec = ns >= 0 ? ns / 1000000000 : (ns - 999999999) / 1000000000;
    return {std::int32_t(sec), std::uint32_t(ns - sec * 1000000000)};
}

LedSettings::LedSettings(const IlluminationSequence& sequence) {
    for (const Illumination& s : sequence) levels.emplace_back(s.levels().begin(), s.levels().end());
    for (auto& l : levels) messages.push_back({sequence_of<dds_sequence_uint8>(l)});
}

void LitFrames::add(const Frame& frame, const builtin_interfaces_msg_dds__Time_& stamp,
                    const vkfuse_msgs_msg_dds__LedSetting_& setting) {
    static const std::string rgb8 = "rgb8";
    vkfuse_msgs_msg_dds__LitFrame_ m{};
    m.image.header = {stamp, text(serial_)};
    m.image.height = std::uint32_t(frame.height);
    m.image.width = std::uint32_t(frame.width);
    m.image.encoding = text(rgb8);
    m.image.is_bigendian = 0;
    m.image.step = std::uint32_t(frame.width) * 3;
    // The frame's bytes themselves: dds_write serializes without writing.
    m.image.data._maximum = m.image.data._length = std::uint32_t(frame.pixels.size());
    m.image.data._buffer = const_cast<std::uint8_t*>(frame.pixels.data());
    m.image.data._release = false;
    m.setting = setting;
    m.index = frame.index;
    m.timestamp = frame.timestamp;
    messages.push_back(m);
}

}  // namespace vkfuse::ros2

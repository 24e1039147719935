// Checks of what a fusion host receives (ros2/remote_checks.hpp).
#include "ros2/remote_checks.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "vkfuse/core/error.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::ros2 {
namespace {

// A received string: at most kMaxNameLength characters, printable.
std::string name_problem(const char* s, const char* what) {
    if (!s) return std::string(what) + " missing";
    const std::size_t n = strnlen(s, kMaxNameLength + 1);
    if (n == 0) return std::string(what) + " empty";
    if (n > kMaxNameLength) return std::string(what) + " over " + std::to_string(kMaxNameLength) + " characters";
    for (std::size_t i = 0; i < n; ++i)
        if (static_cast<unsigned char>(s[i]) < 0x20 || s[i] == 0x7f) return std::string(what) + " holds control characters";
    return "";
}

std::optional<Illumination> setting_of(const vkfuse_msgs_msg_dds__LedSetting_& m, const LedLayout& leds) {
    std::vector<int> levels(m.levels._buffer, m.levels._buffer + m.levels._length);
    Illumination setting(std::move(levels));
    try {
        setting.check(leds);
    } catch (const Error&) {
        return std::nullopt;
    }
    return setting;
}

std::string frame_problem(const vkfuse_msgs_msg_dds__LitFrame_& m, const SensorContract& sensor,
                          const Illumination& expected, Frame& out) {
    const sensor_msgs_msg_dds__Image_& image = m.image;
    const SensorInfo& info = sensor.info;
    if (!image.encoding || std::strcmp(image.encoding, "rgb8") != 0)
        return "encoding " + std::string(image.encoding ? image.encoding : "(none)").substr(0, 32) + ", expected rgb8";
    if (int64_t(image.width) != info.width || int64_t(image.height) != info.height)
        return "a frame of " + std::to_string(image.width) + "x" + std::to_string(image.height) + ", expected " +
               std::to_string(info.width) + "x" + std::to_string(info.height);
    const std::uint64_t step = std::uint64_t(info.width) * 3, bytes = step * std::uint64_t(info.height);
    if (image.step != step) return "step " + std::to_string(image.step) + ", expected " + std::to_string(step);
    if (image.data._length != bytes)
        return std::to_string(image.data._length) + " bytes of rgb8, expected " + std::to_string(bytes);
    const std::optional<Illumination> setting = setting_of(m.setting, info.leds);
    if (!setting || *setting != expected)
        return "a frame lit by " + (setting ? setting->to_string() : std::string("an invalid setting")) + " where " +
               expected.to_string() + " belongs";
    if (!std::isfinite(m.timestamp)) return "a frame timestamp that is not finite";
    out.index = m.index;
    out.timestamp = m.timestamp;
    out.height = info.height;
    out.width = info.width;
    out.pixels.assign(image.data._buffer, image.data._buffer + bytes);
    out.illumination = *setting;
    out.recorded_cycle = -1;
    return "";
}

}  // namespace

std::string seconds_text(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%g s", seconds);
    return text;
}

std::string check_description(const vkfuse_msgs_msg_dds__RigDescription_& msg, DescribedRig& out) {
    out = {};
    if (msg.sensors._length == 0 || msg.sensors._length > kMaxRigSensors)
        return std::to_string(msg.sensors._length) + " sensors, expected 1.." + std::to_string(kMaxRigSensors);
    if (msg.settings._length == 0 || msg.settings._length > kMaxSequenceSettings)
        return std::to_string(msg.settings._length) + " settings, expected 1.." + std::to_string(kMaxSequenceSettings);
    if (msg.background_frames > std::uint32_t(kMaxRemoteBackgroundFrames))
        return std::to_string(msg.background_frames) + " background frames per setting, at most " +
               std::to_string(kMaxRemoteBackgroundFrames);
    out.background_frames = int(msg.background_frames);
    for (std::uint32_t i = 0; i < msg.sensors._length; ++i) {
        const vkfuse_msgs_msg_dds__SensorDescription_& d = msg.sensors._buffer[i];
        for (auto [text, what] : {std::pair{d.serial, "serial"}, {d.model, "model"}, {d.led_model, "LED model"}})
            if (std::string p = name_problem(text, what); !p.empty()) return "sensor " + std::to_string(i) + ": " + p;
        SensorInfo info;
        info.serial = d.serial;
        info.model = d.model;
        if (d.width < 1 || d.height < 1 || d.width > std::uint32_t(kMaxRemoteSide) || d.height > std::uint32_t(kMaxRemoteSide))
            return info.serial + ": frames of " + std::to_string(d.width) + "x" + std::to_string(d.height) +
                   ", expected 1.." + std::to_string(kMaxRemoteSide) + " a side";
        info.width = int(d.width);
        info.height = int(d.height);
        info.fps = std::isfinite(d.fps) && d.fps >= 0 && d.fps <= 1e4 ? d.fps : 0;
        if (d.led_channels._length == 0 || d.led_channels._length > 1024 || d.led_max_level == 0)
            return info.serial + ": an LED layout of " + std::to_string(d.led_channels._length) +
                   " channels up to level " + std::to_string(d.led_max_level);
        info.leds.model = d.led_model;
        info.leds.channels = int(d.led_channels._length);
        info.leds.max_level = d.led_max_level;
        for (std::uint32_t c = 0; c < d.led_channels._length; ++c) {
            if (std::string p = name_problem(d.led_channels._buffer[c], "LED channel name"); !p.empty())
                return info.serial + ": " + p;
            info.leds.names.emplace_back(d.led_channels._buffer[c]);
        }
        if (!out.sensors.empty() && (info.leds.names != out.sensors.front().leds.names ||
                                     info.leds.max_level != out.sensors.front().leds.max_level))
            return info.serial + ": an LED layout unlike " + out.sensors.front().serial + "'s";
        out.sensors.push_back(std::move(info));
    }
    for (std::uint32_t k = 0; k < msg.settings._length; ++k) {
        const std::optional<Illumination> s = setting_of(msg.settings._buffer[k], out.sensors.front().leds);
        if (!s) return "setting " + std::to_string(k) + " does not fit the sensors' LEDs";
        out.sequence.push_back(*s);
    }
    // What one sample of each kind would take, against DDS's bound.
    for (const SensorInfo& s : out.sensors) {
        const std::uint64_t bytes = 3ull * std::uint64_t(s.width) * std::uint64_t(s.height);
        const std::uint64_t background = bytes * distinct_settings(out.sequence).size() * std::uint64_t(out.background_frames);
        if (bytes * out.sequence.size() > kMaxSampleBytes || background > kMaxSampleBytes)
            return s.serial + ": its cycles or background would exceed " + std::to_string(kMaxSampleBytes >> 20) +
                   " MiB a sample";
    }
    return "";
}

std::string check_cycle(const vkfuse_msgs_msg_dds__LitCycle_& msg, const SensorContract& sensor, std::vector<Frame>& out) {
    out.clear();
    if (!msg.serial || sensor.info.serial != msg.serial) return "a cycle of another serial";
    if (msg.frames._length != sensor.sequence.size())
        return "cycle " + std::to_string(msg.cycle) + " of " + std::to_string(msg.frames._length) + " frames, expected " +
               std::to_string(sensor.sequence.size());
    out.resize(sensor.sequence.size());
    for (std::size_t k = 0; k < sensor.sequence.size(); ++k)
        if (std::string p = frame_problem(msg.frames._buffer[k], sensor, sensor.sequence[k], out[k]); !p.empty()) {
            out.clear();
            return "cycle " + std::to_string(msg.cycle) + ", frame " + std::to_string(k) + ": " + p;
        }
    return "";
}

std::string check_background(const vkfuse_msgs_msg_dds__Background_& msg, const SensorContract& sensor,
                             std::vector<std::pair<Illumination, std::vector<Frame>>>& out) {
    out.clear();
    if (!msg.serial || sensor.info.serial != msg.serial) return "a background of another serial";
    const IlluminationSequence settings = distinct_settings(sensor.sequence);
    const std::size_t n = std::size_t(sensor.background_frames);
    if (msg.frames_per_setting != n || msg.frames._length != n * settings.size())
        return "a background of " + std::to_string(msg.frames._length) + " frames, " +
               std::to_string(msg.frames_per_setting) + " per setting; expected " + std::to_string(n) + " of each of " +
               std::to_string(settings.size()) + " settings";
    for (std::size_t s = 0; s < settings.size(); ++s) {
        out.emplace_back(settings[s], std::vector<Frame>(n));
        for (std::size_t j = 0; j < n; ++j)
            if (std::string p = frame_problem(msg.frames._buffer[s * n + j], sensor, settings[s], out.back().second[j]);
                !p.empty()) {
                out.clear();
                return "background frame " + std::to_string(s * n + j) + ": " + p;
            }
    }
    return "";
}

}  // namespace vkfuse::ros2

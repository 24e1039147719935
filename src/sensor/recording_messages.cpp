// RecordedFrame and FusionMetrics in CDR, field by field as their .msg files
// (ros2/vkfuse_msgs/msg) order them; the independent test (tests/mcap)
// decodes them with Foxglove's CDR reader from the recorded schemas.
#include "sensor/recording_messages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/cdr.hpp"
#include "io/limits.hpp"
#include "sensor/ros2_names.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse::sensor::recording {
namespace {

constexpr std::uint8_t kStatusOk = 0, kStatusTimeout = 1, kStatusFailed = 2;

}  // namespace

std::string frame_topic(const std::string& serial) { return "/vkfuse/" + ros2_topic_token(serial) + "/frame"; }
std::string metrics_topic(const std::string& serial) { return "/vkfuse/" + ros2_topic_token(serial) + "/metrics"; }

std::uint64_t frame_time_ns(double timestamp) {
    // Up to 2^31 s: what a ROS 2 stamp's int32 seconds hold.
    if (!(timestamp > 0)) return 0;
    return std::uint64_t(std::min(timestamp, 2147483647.0) * 1e9);
}

std::string encode_frame(const std::string& serial, const Frame& frame, const Illumination& lit_by,
                         const std::string& object, bool background, std::int64_t cycle) {
    io::cdr::Writer w;
    w.header(frame_time_ns(frame.timestamp), serial);
    w.num(std::uint32_t(frame.height)).num(std::uint32_t(frame.width)).str("rgb8").num(std::uint8_t(0));
    w.num(std::uint32_t(frame.width) * 3u).octets(frame.pixels.data(), frame.pixels.size());
    w.count(lit_by.levels().size());
    for (int level : lit_by.levels()) w.num(std::uint8_t(level));
    w.num(std::uint64_t(frame.index)).num(frame.timestamp);
    w.str(object).num(std::uint8_t(background)).num(std::int64_t(cycle));
    return w.take();
}

std::optional<DecodedFrame> decode_frame(std::string_view payload, std::string& why) {
    io::cdr::Reader r(payload);
    DecodedFrame f;
    r.num<std::int32_t>();
    r.num<std::uint32_t>();
    f.serial = r.str();
    const std::uint32_t height = r.num<std::uint32_t>(), width = r.num<std::uint32_t>();
    const std::string_view encoding = r.str();
    const std::uint8_t big_endian = r.num<std::uint8_t>();
    const std::uint32_t step = r.num<std::uint32_t>();
    f.pixels = r.octets();
    std::vector<int> levels(r.count(1));
    for (int& l : levels) l = r.num<std::uint8_t>();
    f.illumination = Illumination(std::move(levels));
    f.index = r.num<std::uint64_t>();
    f.timestamp = r.num<double>();
    f.object = r.str();
    f.background = r.num<std::uint8_t>() != 0;
    f.cycle = r.num<std::int64_t>();
    if (r.failed()) {
        why = "not a RecordedFrame (its fields run past the message)";
        return std::nullopt;
    }
    if (encoding != "rgb8" || big_endian != 0) {
        why = "image encoding \"" + std::string(encoding.substr(0, 32)) + "\" (expected rgb8)";
        return std::nullopt;
    }
    if (height == 0 || width == 0 || std::uint64_t(height) * width > io::kMaxSamples || step != std::uint64_t(width) * 3 ||
        f.pixels.size() != std::uint64_t(step) * height) {
        why = "image " + std::to_string(width) + "x" + std::to_string(height) + ", step " + std::to_string(step) +
              ", with " + std::to_string(f.pixels.size()) + " bytes of pixels (expected step 3 x width and step x height bytes)";
        return std::nullopt;
    }
    f.height = int(height);
    f.width = int(width);
    return f;
}

std::string encode_rig(const Dataset& dataset, std::uint64_t time_ns) {
    io::cdr::Writer w;
    w.header(time_ns, "");
    w.count(dataset.sensors.size());
    for (const DatasetSensorRecord& record : dataset.sensors) {
        const SensorInfo& s = record.info;
        w.str(s.serial).str(ros2_topic_token(s.serial)).str(s.model).num(s.fps);
        w.num(std::uint32_t(s.width)).num(std::uint32_t(s.height)).str(s.leds.model).count(s.leds.names.size());
        for (const std::string& name : s.leds.names) w.str(name);
        w.num(std::uint16_t(s.leds.max_level));
    }
    const DatasetRun* run = dataset.run ? &*dataset.run : nullptr;
    w.count(run ? run->sequence.size() : 0);
    if (run)
        for (const Illumination& setting : run->sequence) {
            w.count(setting.levels().size());
            for (int level : setting.levels()) w.num(std::uint8_t(level));
        }
    w.str(run ? method_label(run->fusion) : "").num(std::uint8_t(0)).count(0).str("").num(0.0);
    w.num(std::uint32_t(run ? run->background_frames : 0)).num(std::uint8_t(1));
    return w.take();
}

std::string encode_miss(const std::string& serial, const DatasetMiss& miss, std::uint64_t time_ns) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    io::cdr::Writer w;
    w.header(time_ns, serial);
    w.str(serial).num(std::uint64_t(miss.cycle)).num(miss.status == "timeout" ? kStatusTimeout : kStatusFailed);
    w.str(miss.error).str("").count(0);
    w.num(nan).num(nan).num(nan);
    w.num(std::uint8_t(0)).num(std::uint8_t(0)).num(std::uint8_t(0));
    w.num(0.0).num(0.0).num(0.0);
    return w.take();
}

std::optional<DatasetMiss> decode_miss(std::string_view payload, std::string& serial, std::string& why) {
    io::cdr::Reader r(payload);
    r.num<std::int32_t>();
    r.num<std::uint32_t>();
    r.str();
    serial = r.str();
    DatasetMiss miss;
    const std::uint64_t cycle = r.num<std::uint64_t>();
    const std::uint8_t status = r.num<std::uint8_t>();
    miss.error = r.str();
    if (r.failed() || cycle > (std::uint64_t(1) << 53) || status > kStatusFailed) {
        why = "not a FusionMetrics this reader takes";
        return std::nullopt;
    }
    if (status == kStatusOk) return std::nullopt;
    miss.cycle = std::int64_t(cycle);
    miss.status = status == kStatusTimeout ? "timeout" : "failed";
    return miss;
}

}  // namespace vkfuse::sensor::recording

// vkfuse/ros2/publisher.hpp - a rig's cycles on ROS 2's wire: a DDS
// participant (Cyclone DDS) that speaks ROS 2's names and types, so every
// ROS 2 node on the network subscribes to it as to any ROS 2 publisher, with
// no ROS installed here. Built as vkfuse::ros2 where Cyclone DDS is found;
// the other libraries never depend on it. The topics (README, "Rigs across machines: ROS 2"):
//
//   /vkfuse/<token>/fused       sensor_msgs/msg/Image (rgb8, or 32FC3); the last 3 kept
//   /vkfuse/<token>/metrics     vkfuse_msgs/msg/FusionMetrics; the last 20 kept
//   /vkfuse/<token>/cycle       vkfuse_msgs/msg/LitCycle (frames: on); the last 3 kept
//   /vkfuse/<token>/background  vkfuse_msgs/msg/Background (frames: on); the last one kept
//   /vkfuse/rig                 vkfuse_msgs/msg/RigDescription; the last one kept
//   /diagnostics                diagnostic_msgs/msg/DiagnosticArray, once a second
//
// A rig that fuses nothing (a capture host) has no fused and metrics topics.
// All reliable; the topics that keep samples are transient local, so a
// subscriber that asks for it gets them when it joins (a volatile one, ROS
// 2's default, matches too). Every writer asserts its liveliness at least
// every kLivelinessLease: a subscriber knows within that time that this
// process is gone, however it ended.
//
// The message definitions ship as a ROS 2 interface package (ros2/vkfuse_msgs).
#pragma once
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/core/skip.hpp"
#include "vkfuse/rig/rig.hpp"
#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse::ros2 {

// How fused images travel: rgb8 holds the samples a PNG of --out holds
// (round(clamp(v, 0, 1) * 255)); 32FC3 the float32 samples themselves.
enum class ImageEncoding { Rgb8, Float32 };
inline std::string_view to_string(ImageEncoding encoding) { return encoding == ImageEncoding::Rgb8 ? "rgb8" : "32FC3"; }
inline std::optional<ImageEncoding> parse_image_encoding(std::string_view name) {
    for (ImageEncoding e : {ImageEncoding::Rgb8, ImageEncoding::Float32})
        if (to_string(e) == name) return e;
    return std::nullopt;
}

// DDS domains whose ports fit the RTPS port formula (7400 + 250 d + ...).
inline constexpr int kMaxDomain = 232;
// A domain as ROS_DOMAIN_ID or an option spells it: 0..kMaxDomain, else
// nullopt. (Header-only, so a program built without vkfuse::ros2 checks
// its options the same way.)
inline std::optional<int> parse_domain(std::string_view text) {
    if (text.empty() || text.size() > 3 || text.find_first_not_of("0123456789") != std::string_view::npos)
        return std::nullopt;
    const int d = std::stoi(std::string(text));
    return d <= kMaxDomain ? std::optional<int>(d) : std::nullopt;
}

// A serial as one token of a ROS 2 name, which allows letters, digits and
// underscores and no leading digit: every other character becomes '_', and
// a leading digit gets "sensor_" before it ("SIM-0001" -> "SIM_0001",
// "2023.7" -> "sensor_2023_7"). The messages carry the serial itself.
std::string topic_token(std::string_view serial);

// How soon a subscriber learns that a publisher is gone (killed, or its
// host off the network): its writers' liveliness lease.
inline constexpr std::chrono::milliseconds kLivelinessLease{500};

// What /vkfuse/rig describes, and what the topics are named after.
struct RigTopics {
    std::vector<SensorInfo> sensors;  // serials unique, and their tokens too
    IlluminationSequence sequence;
    FusionSpec fusion;
    MetricSet metrics;
    SkipConfig skip;
    int background_frames = 0;  // per setting (RigConfig::background_frames)
    bool fused = true;          // false: a capture host (RigConfig::fuse)
};

struct PublisherOptions {
    int domain = 0;
    ImageEncoding encoding = ImageEncoding::Rgb8;
    // Each sensor's cycles (/vkfuse/<token>/cycle) and background
    // (/vkfuse/<token>/background) too, for a fusion host on another machine.
    bool frames = false;
};

// When sensor's frame stamped `timestamp` (seconds on the sensor's clock)
// began its exposure, on the system clock: what header.stamp says.
using CaptureTime = std::function<std::chrono::system_clock::time_point(std::size_t sensor, double timestamp)>;

// Samples the publisher handed to DDS, and those DDS refused (a writer that
// stayed blocked on a reliable subscriber past its time, or out of resources).
struct PublisherCounts {
    std::uint64_t written = 0;
    std::uint64_t dropped = 0;
};

class RigPublisher {
public:
    // Joins the domain and creates every topic's writer; publishes
    // /vkfuse/rig at once. Throws Error(InvalidArgument) for two sensors
    // whose serials share a token, Error(Device) naming what DDS refused.
    // capture_time dates frames (empty: every frame is dated when published).
    RigPublisher(const RigTopics& rig, const PublisherOptions& options, CaptureTime capture_time = {});
    ~RigPublisher();
    RigPublisher(const RigPublisher&) = delete;
    RigPublisher& operator=(const RigPublisher&) = delete;

    // One cycle: each sensor's metrics, its fused image where the cycle has
    // one, its frames (options.frames) where it delivered; /diagnostics when
    // a second passed since it was last sent. header.stamp: the capture time
    // of the sensor's newest frame, when the cycle was complete, as
    // SensorCycle::newest_timestamp() and metrics.jsonl date it (now, where
    // it delivered none).
    void publish(const CycleResult& cycle);

    // With options.frames: one setting's background frames of a sensor (as
    // RigConfig::on_background hands them over). Once every distinct setting
    // of the sequence has come, /vkfuse/<token>/background is published,
    // from a thread of the publisher's own, so the caller goes on at once
    // (the destructor waits until it is written). Sensors may call it from
    // their own threads at once.
    void publish_background(std::size_t sensor, const Illumination& setting, const std::vector<Frame>& frames);

    // Whether every topic of sensor's (fused, metrics, or cycle and
    // background) has a subscriber: what a caller may wait for before its
    // first cycle.
    bool has_subscribers(std::size_t sensor) const;
    PublisherCounts counts() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse::ros2

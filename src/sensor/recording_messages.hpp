// sensor/recording_messages.hpp - what an MCAP recording holds, in ROS 2's
// types and CDR, named as vkfuse/ros2/publisher.hpp names its topics:
//
//   /vkfuse/<token>/frame    vkfuse_msgs/msg/RecordedFrame  every frame, backgrounds included
//   /vkfuse/<token>/metrics  vkfuse_msgs/msg/FusionMetrics  the cycles the sensor missed
//   /vkfuse/rig              vkfuse_msgs/msg/RigDescription once, at the first frame's time
//
// and one Metadata record, "vkfuse.dataset", holding the dataset's manifest
// (docs: "Datasets") without its frames: the sensors, the source, the run.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::sensor::recording {

inline constexpr std::string_view kFrameType = "vkfuse_msgs/msg/RecordedFrame";
inline constexpr std::string_view kMetricsType = "vkfuse_msgs/msg/FusionMetrics";
inline constexpr std::string_view kRigType = "vkfuse_msgs/msg/RigDescription";
inline constexpr std::string_view kRigTopic = "/vkfuse/rig";
inline constexpr std::string_view kMetadataName = "vkfuse.dataset";
inline constexpr std::string_view kManifestKey = "manifest";

std::string frame_topic(const std::string& serial);
std::string metrics_topic(const std::string& serial);

// A frame's time on the recording's axis: its exposure start on the sensor's
// clock, in nanoseconds (negative or non-finite timestamps: 0).
std::uint64_t frame_time_ns(double timestamp);

// RecordedFrame, CDR. header.frame_id: serial; the image rgb8, step 3 * width.
std::string encode_frame(const std::string& serial, const Frame& frame, const Illumination& lit_by,
                         const std::string& object, bool background, std::int64_t cycle);

struct DecodedFrame {
    std::string serial, object;
    bool background = false;
    std::int64_t cycle = -1;
    std::uint64_t index = 0;
    double timestamp = 0;
    Illumination illumination;
    int height = 0, width = 0;
    std::string_view pixels;  // into the payload: height * width * 3 bytes
};
// Every field checked (sizes within the payload, rgb8, step, pixel count);
// nullopt with why set when the payload is not a RecordedFrame this reader takes.
std::optional<DecodedFrame> decode_frame(std::string_view payload, std::string& why);

// RigDescription, CDR, as `vkfuse run --publish` describes its rig: the
// sensors, and the run's sequence, method and background frames (empty for a
// dataset without a run). fused false and frames true: a recording holds
// each sensor's frames, backgrounds included, and no fused image; metrics and
// skip empty, since its replay chooses them.
std::string encode_rig(const Dataset& dataset, std::uint64_t time_ns);

// FusionMetrics for a cycle the sensor missed (status TIMEOUT or FAILED, NaN metrics).
std::string encode_miss(const std::string& serial, const DatasetMiss& miss, std::uint64_t time_ns);
// The miss a FusionMetrics payload reports; nullopt with why empty for a
// fused cycle's metrics, with why set for a payload that is not FusionMetrics.
std::optional<DatasetMiss> decode_miss(std::string_view payload, std::string& serial, std::string& why);

}  // namespace vkfuse::sensor::recording

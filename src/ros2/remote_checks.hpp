// ros2/remote_checks.hpp - what a fusion host accepts from the network: a
// capture host's description, its sensors' cycles and backgrounds, each
// checked whole before any of it is used. A check returns the problem in one
// line (empty: the sample is sound).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "vkfuse/ros2/remote.hpp"
#include "vkfuse_msgs.h"

namespace vkfuse::ros2 {

// Bounds on what a description may ask of this host, whoever sent it.
inline constexpr int kMaxRemoteSide = 4096;           // frame width, height
inline constexpr int kMaxRemoteBackgroundFrames = 1000;  // per setting
inline constexpr std::size_t kMaxNameLength = 256;    // serials, models, channel names

// One capture host's description of the sensors it publishes frames of, or
// the problem with it.
struct DescribedRig {
    std::vector<SensorInfo> sensors;
    IlluminationSequence sequence;
    int background_frames = 0;
};
std::string check_description(const vkfuse_msgs_msg_dds__RigDescription_& msg, DescribedRig& out);

// What a sensor's samples must match.
struct SensorContract {
    SensorInfo info;
    IlluminationSequence sequence;
    int background_frames = 0;
};

// A LitCycle of the sensor: its K frames in sequence order, or the problem.
std::string check_cycle(const vkfuse_msgs_msg_dds__LitCycle_& msg, const SensorContract& sensor, std::vector<Frame>& out);
// A Background of the sensor: its frames by setting (in the order of the
// sequence's distinct settings), or the problem.
std::string check_background(const vkfuse_msgs_msg_dds__Background_& msg, const SensorContract& sensor,
                             std::vector<std::pair<Illumination, std::vector<Frame>>>& out);

// "1 s", "0.5 s": a time in a line.
std::string seconds_text(double seconds);

}  // namespace vkfuse::ros2

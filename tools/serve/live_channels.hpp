// serve/live_channels.hpp - what `vkfuse run --serve` publishes, as Foxglove
// channels (ids from 1, in this order):
//
//   per sensor <token> (the serial as a ROS 2 name token, as on ROS 2's wire)
//     /vkfuse/<token>/fused               sensor_msgs/msg/Image (cdr, rgb8: the --out PNG's samples)
//     /vkfuse/<token>/fused/compressed    sensor_msgs/msg/CompressedImage (cdr, png: the --out PNG itself)
//     /vkfuse/<token>/lit/led_<r>_<g>_<b> sensor_msgs/msg/Image (cdr, rgb8), one per setting of the sequence
//     .../led_<r>_<g>_<b>/compressed      sensor_msgs/msg/CompressedImage (cdr, jpeg): the same, a
//                                         tenth of the bytes (image_transport's name for it)
//   The page takes the compressed ones: what a browser on the rig's own host
//   costs the rig is mostly the bytes it receives.
//     /vkfuse/<token>/metrics             vkfuse.Metrics (json): the cycle's metrics.jsonl line
//   /vkfuse/status                        vkfuse.RigStatus (json): rates, fractions, late sensors, errors
//   /vkfuse/rig                           vkfuse.Rig (json): sensors, sequence, method, static setting
//
// Images are ROS 2's own type, so Foxglove's Image panel shows them as it
// shows a ROS 2 camera; the JSON ones carry their JSON schema.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "serve/foxglove_protocol.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::cli::serve {

struct LiveRig {
    std::vector<SensorInfo> sensors;
    IlluminationSequence sequence;
    std::string method;       // as --method/--wavelet spell it
    std::string object;
    std::size_t static_slot;  // the sequence's static setting (every LED full), else 0
    bool skipping = false;
};

struct ChannelRole {
    enum Kind { Fused, FusedPng, Lit, LitJpeg, Metrics, Status, Rig } kind = Status;
    std::size_t sensor = 0, slot = 0;  // Fused, Lit, Metrics: the sensor; Lit: the sequence slot
};

class LiveChannels {
public:
    explicit LiveChannels(const LiveRig& rig);
    const std::vector<Channel>& channels() const { return channels_; }
    const ChannelRole& role(std::uint32_t channel) const { return roles_.at(channel - 1); }
    const LiveRig& rig() const { return rig_; }
    // /vkfuse/rig's one message.
    std::string rig_json() const;

private:
    LiveRig rig_;
    std::vector<Channel> channels_;
    std::vector<ChannelRole> roles_;
};

// One cycle as the server publishes it, copied on the rig's thread (only
// what some client subscribed to; the rest stays empty) and encoded on the
// server's own.
struct LiveCycle {
    std::uint64_t cycle = 0;
    std::chrono::system_clock::time_point at;
    double capture_wait_s = 0, fuse_s = 0;
    struct Sensor {
        std::string serial;
        SensorStatus status = SensorStatus::Ok;
        std::string error;
        std::string metrics_line;           // empty: not wanted
        std::vector<std::vector<std::uint8_t>> lit;  // per slot; empty: not wanted or not captured
        Image fused;                        // as fused; empty: not wanted or not fused
        int height = 0, width = 0;
        bool idle = false, reused = false, watch = false;
        double fused_fraction = 0;
    };
    std::vector<Sensor> sensors;
};

// sensor_msgs/msg/Image, CDR, rgb8: frame_id the serial, stamp the time.
std::string image_cdr(const std::string& frame_id, std::chrono::system_clock::time_point at, int height, int width,
                      const std::uint8_t* rgb);
// sensor_msgs/msg/CompressedImage, CDR, format jpeg.
std::string jpeg_cdr(const std::string& frame_id, std::chrono::system_clock::time_point at, int height, int width,
                     const std::uint8_t* rgb);
// The same of a fused image, as its --out PNG holds it (io::to_8bit).
std::string image_cdr(const std::string& frame_id, std::chrono::system_clock::time_point at, const Image& fused);
// sensor_msgs/msg/CompressedImage, CDR, format png: the fused image's --out PNG, byte for byte.
std::string png_cdr(const std::string& frame_id, std::chrono::system_clock::time_point at, const Image& fused);

// The rig's status over a sliding window of cycles (the server's thread only).
class RigStatus {
public:
    explicit RigStatus(std::size_t sensors) : late_(sensors, 0) {}
    void add(const LiveCycle& cycle);
    std::string json() const;

private:
    struct Seen {
        std::chrono::system_clock::time_point at;
        std::size_t fused = 0, idle = 0, reused = 0, delivered = 0;
    };
    std::vector<Seen> window_;  // the last seconds
    std::vector<std::uint64_t> late_;
    std::vector<std::string> states_, errors_;
    std::uint64_t cycle_ = 0;
    double capture_wait_s_ = 0, fuse_s_ = 0;
};

}  // namespace vkfuse::cli::serve

// vkfuse/ros2/remote.hpp - sensors captured on another host, as a rig here
// drives its own: a capture host (`vkfuse run --capture-only --publish ros2
// --publish-frames`) publishes each sensor's cycles and background on ROS 2's
// wire (vkfuse/ros2/publisher.hpp); a RemoteRig subscribes to them and offers
// every sensor as a vkfuse::Sensor whose frames carry their setting, so a Rig
// judging frames by label (FrameJudging::Label) fuses, skips and records them
// exactly as it does a recorded dataset's.
//
// Everything received is input from the network: a sample is checked against
// the capture host's /vkfuse/rig (sizes, encoding, settings, serial, cycle
// numbers) before a byte of it is used, and what fails is dropped, counted
// and said in one line (at most one a second per sensor). Each sensor keeps
// a few cycles (the newest: a fusion host that falls behind skips cycles,
// counted, rather than fusing ever older ones; RemoteRigOptions::queue_cycles),
// and DDS itself
// refuses samples over kMaxSampleBytes. DDS has no authentication here: any
// host in the domain can publish; keep rigs on their own domain and network
// interface (README, "Rigs across machines").
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "vkfuse/rig/rig.hpp"
#include "vkfuse/sensor/illumination.hpp"
#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse::ros2 {

// The largest sample this process's DDS domain takes in or sends: 16
// settings of 1920x1080 frames, with room to spare.
inline constexpr std::uint64_t kMaxSampleBytes = 128ull << 20;

struct RemoteRigOptions {
    int domain = 0;
    // The sensors to fuse, by serial; empty: every sensor of the first
    // capture host heard.
    std::vector<std::string> serials;
    // How long the start waits for the capture hosts' /vkfuse/rig, and then
    // each sensor for its background.
    double startup_timeout_s = 60;
    // Cycles each sensor keeps received and not yet fused, for a fusion host
    // that falls behind for a moment; the oldest go first (and are counted
    // missed). Few keep a lagging host's results fresh (a live rig); more
    // ride out longer stalls (a replay that must arrive whole). Never more
    // than fit queue_bytes, and at least 1.
    int queue_cycles = 4;
    std::uint64_t queue_bytes = 64ull << 20;
    // Where each problem's line goes (at most one a second per sensor; the
    // rest are counted): "<serial>: <problem>". Empty: standard error.
    std::function<void(const std::string& line)> report;
};

// What the capture hosts run, from their /vkfuse/rig.
struct RemoteDescription {
    std::vector<SensorInfo> sensors;  // those options.serials asked for, in that order
    IlluminationSequence sequence;
    int background_frames = 0;
};

// Per sensor, since the start.
struct RemoteCounts {
    std::uint64_t cycles = 0;     // whole, checked cycles received
    std::uint64_t missed = 0;     // cycles the capture host published that never arrived (or were overtaken)
    std::uint64_t malformed = 0;  // samples refused by the checks
    std::uint64_t lost = 0;       // times the capture host went away (its liveliness lapsed)
};

class RemoteRig {
public:
    // Joins the domain and waits (startup_timeout_s at most) until capture
    // hosts that publish frames describe every serial asked for. Throws
    // Error(Timeout) naming what never came, Error(InvalidArgument) for a
    // description that cannot be served (two capture hosts with different
    // sequences, sizes over the bounds), Error(Device) naming what DDS refused.
    explicit RemoteRig(const RemoteRigOptions& options);
    ~RemoteRig();
    RemoteRig(const RemoteRig&) = delete;
    RemoteRig& operator=(const RemoteRig&) = delete;

    const RemoteDescription& description() const;
    // One per described sensor. Each grab() takes the next frame of a whole
    // cycle received (waiting for one); a cycle's frames are handed out in
    // sequence order and never mixed with another cycle's. Its background
    // frames come first. grab() throws Error(Unplugged) when the capture host
    // is gone (within kLivelinessLease) and Error(Timeout) when nothing came
    // for a while, so a Rig reports the sensor and takes it back once its
    // capture host publishes again. Its clock maps the sensor's timestamps to
    // the capture host's system clock (the stamps its frames carry), so what
    // this host publishes is dated by capture, as the capture host dates it
    // (hosts' clocks kept in step by NTP or PTP).
    std::vector<RigSensor> sensors() const;
    RemoteCounts counts(std::size_t sensor) const;

    struct Impl;

private:
    std::shared_ptr<Impl> impl_;
};

}  // namespace vkfuse::ros2

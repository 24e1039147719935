// ros2/remote_sensor.hpp - one sensor of a capture host, read from its
// /vkfuse/<token>/cycle and /vkfuse/<token>/background (vkfuse/ros2/remote.hpp).
#pragma once
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "ros2/dds_entities.hpp"
#include "ros2/remote_checks.hpp"
#include "vkfuse/sensor/clock.hpp"
#include "vkfuse/ros2/remote.hpp"

namespace vkfuse::ros2 {

// What every sensor of a RemoteRig shares; the last owner deletes the
// participant (and with it every reader), after the sensors' threads are done
// with it.
struct RemoteDomain {
    DdsEntity domain;  // set where this process's domain was made here (configured_domain)
    DdsEntity participant;
    std::atomic<bool> closing{false};  // the RemoteRig is gone: waits end at once
    std::function<void(const std::string&)> report;
};

// A remote sensor's clock: now() is the sensor's time as its last cycle
// dates it (frame timestamp against its capture stamp on the capture host's
// system clock), so `now() - timestamp` is a frame's age.
class RemoteClock : public Clock {
public:
    double now() const override;
    void wait_until(double seconds) override;
    // A frame stamped `timestamp` on the sensor's clock was exposed at `system` (s since the epoch).
    void observe(double timestamp, double system) { offset_ = timestamp - system; }

private:
    std::atomic<double> offset_{0};
};

class RemoteSensor : public Sensor {
public:
    RemoteSensor(std::shared_ptr<RemoteDomain> domain, SensorContract contract, const RemoteRigOptions& options);
    SensorInfo info() const override { return contract_.info; }
    void set_illumination(const Illumination& setting) override { requested_ = setting; }
    Frame grab() override;
    RemoteCounts counts() const;
    std::shared_ptr<Clock> clock() const { return clock_; }

private:
    Frame next_background_frame();
    std::vector<Frame> next_cycle();
    // A sound cycle from the reader's next sample, or nothing (counted).
    std::optional<std::vector<Frame>> take_cycle();
    std::uint64_t participant_of(dds_instance_handle_t publication) const;
    // Publishers of the cycle topic alive now (nullopt where DDS cannot say).
    std::optional<std::int32_t> live_publishers() const;
    // "<serial>: <what>", unless a line went out less than a second ago.
    void say_now_and_then(const std::string& what);
    // A sample refused: counted, and said now and then.
    void problem(const std::string& what);

    std::shared_ptr<RemoteDomain> domain_;
    std::shared_ptr<RemoteClock> clock_ = std::make_shared<RemoteClock>();
    SensorContract contract_;
    std::string topic_;  // /vkfuse/<token>
    double startup_timeout_s_;
    DdsEntity cycles_, background_;
    DataWait cycle_arrived_;
    std::optional<DataWait> background_arrived_;  // until the background is taken
    Illumination requested_;
    // The background, by setting, until every frame of it was handed out.
    std::vector<std::pair<Illumination, std::vector<Frame>>> background_frames_;
    std::vector<std::size_t> background_served_;
    bool background_done_ = false;
    std::vector<Frame> cycle_;  // the cycle being handed out
    std::size_t position_ = 0;
    dds_instance_handle_t publication_ = 0;  // whose cycles we follow
    std::uint64_t origin_ = 0;  // Frame::origin of its cycles: publication_'s participant
    std::optional<std::uint64_t> last_cycle_;
    bool alive_ = false;
    bool away_ = false;  // said gone, not yet back
    std::chrono::steady_clock::time_point last_line_{};
    mutable std::mutex counts_mutex_;
    RemoteCounts counts_;
};

}  // namespace vkfuse::ros2

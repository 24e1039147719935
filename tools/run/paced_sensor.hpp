// paced_sensor.hpp - a recorded sensor played at the pace it was recorded
// (`vkfuse run --replay DIR --realtime`): each frame is handed over when as
// much wall time has passed since the first as its timestamp says, as the
// sensor itself delivered it. What a capture host replaying a recording
// must do for a fusion host to see a live rig's rate.
#pragma once
#include <atomic>
#include <memory>

#include "vkfuse/sensor/clock.hpp"
#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse::cli {

// Also the sensor's clock: now() is the recording's time being played, so a
// frame's age (now() - timestamp) dates it on the system clock.
class PacedSensor : public Sensor, public Clock {
public:
    explicit PacedSensor(std::shared_ptr<Sensor> recorded);
    SensorInfo info() const override { return recorded_->info(); }
    void set_illumination(const Illumination& setting) override { recorded_->set_illumination(setting); }
    Frame grab() override;
    double now() const override;
    void wait_until(double seconds) override;

private:
    std::shared_ptr<Sensor> recorded_;
    std::shared_ptr<Clock> wall_ = make_real_clock();
    // Recording time minus wall time, from the first frame on.
    std::atomic<double> offset_{0};
    bool started_ = false;  // touched by the capture thread only
};

}  // namespace vkfuse::cli

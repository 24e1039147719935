#include "run/paced_sensor.hpp"

namespace vkfuse::cli {

PacedSensor::PacedSensor(std::shared_ptr<Sensor> recorded) : recorded_(std::move(recorded)) {}

Frame PacedSensor::grab() {
    Frame f = recorded_->grab();
    if (!started_) {
        offset_ = f.timestamp - wall_->now();
        started_ = true;
    }
    wait_until(f.timestamp);
    return f;
}

double PacedSensor::now() const { return wall_->now() + offset_.load(); }

void PacedSensor::wait_until(double seconds) { wall_->wait_until(seconds - offset_.load()); }

}  // namespace vkfuse::cli

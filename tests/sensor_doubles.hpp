// sensor_doubles.hpp - sensors wrapped for tests: one that logs the simulator's
// ground truth of every frame it hands out, one that fails on cue, one that
// is unplugged and plugged back on cue.
#pragma once
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "vkfuse/core/error.hpp"

#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::test {

// Forwards to a SimDigit and keeps the truth of every grabbed frame, taken on
// the grabbing thread right away (the simulator keeps only recent ones).
class TruthLoggingSensor : public Sensor {
public:
    explicit TruthLoggingSensor(std::shared_ptr<SimDigit> sim) : sim_(std::move(sim)) {}
    SensorInfo info() const override { return sim_->info(); }
    void set_illumination(const Illumination& s) override { sim_->set_illumination(s); }
    Frame grab() override {
        Frame f = sim_->grab();
        std::lock_guard lock(mutex_);
        truths_.emplace(f.index, sim_->truth(f.index));
        return f;
    }
    SimFrameTruth truth(std::uint64_t index) const {
        std::lock_guard lock(mutex_);
        return truths_.at(index);
    }

private:
    std::shared_ptr<SimDigit> sim_;
    mutable std::mutex mutex_;
    std::map<std::uint64_t, SimFrameTruth> truths_;
};

// Forwards to a sensor until grab number `after`, then throws (Throw) or
// blocks until release() (Stall).
class FaultySensor : public Sensor {
public:
    enum class Fault { Throw, Stall };
    FaultySensor(std::shared_ptr<Sensor> inner, Fault fault, int after)
        : inner_(std::move(inner)), fault_(fault), after_(after) {}
    ~FaultySensor() override { release(); }

    SensorInfo info() const override { return inner_->info(); }
    void set_illumination(const Illumination& s) override { inner_->set_illumination(s); }
    Frame grab() override {
        if (grabs_++ >= after_) {
            if (fault_ == Fault::Throw) throw std::runtime_error("USB transfer failed (test fault)");
            std::unique_lock lock(mutex_);
            stalled_ = true;
            changed_.notify_all();
            changed_.wait(lock, [&] { return released_; });
        }
        return inner_->grab();
    }
    bool stalled() const {
        std::lock_guard lock(mutex_);
        return stalled_;
    }
    void release() {
        std::lock_guard lock(mutex_);
        released_ = true;
        changed_.notify_all();
    }

private:
    std::shared_ptr<Sensor> inner_;
    Fault fault_;
    int after_;
    int grabs_ = 0;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    bool stalled_ = false, released_ = false;
};

// Forwards to a sensor, except between unplug() and replug(): then grab()
// waits a little, as a real one looks for its device, and throws
// Error(Unplugged) naming the serial.
class UnpluggableSensor : public Sensor {
public:
    explicit UnpluggableSensor(std::shared_ptr<Sensor> inner) : inner_(std::move(inner)) {}

    SensorInfo info() const override { return inner_->info(); }
    void set_illumination(const Illumination& s) override { inner_->set_illumination(s); }
    Frame grab() override {
        {
            std::lock_guard lock(mutex_);
            if (!unplugged_) return inner_->grab();
            ++refused_;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        throw Error(ErrorKind::Unplugged, info().serial + ": unplugged (test)");
    }
    void unplug() { set(true); }
    void replug() { set(false); }
    int refused() const {
        std::lock_guard lock(mutex_);
        return refused_;
    }

private:
    void set(bool unplugged) {
        std::lock_guard lock(mutex_);
        unplugged_ = unplugged;
    }
    std::shared_ptr<Sensor> inner_;
    mutable std::mutex mutex_;
    bool unplugged_ = false;
    int refused_ = 0;
};

}  // namespace vkfuse::test

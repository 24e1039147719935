// Real and virtual clocks (include/vkfuse/sensor/clock.hpp).
#include <algorithm>
#include <chrono>
#include <mutex>
#include <thread>

#include "core/deadline.hpp"
#include "vkfuse/sensor/clock.hpp"

namespace vkfuse {
namespace {

class RealClock final : public Clock {
public:
    double now() const override { return std::chrono::duration<double>(Steady::now() - start_).count(); }

    void wait_until(double seconds) override {
        std::this_thread::sleep_until(deadline_after<Steady>(start_, seconds));
    }

private:
    using Steady = std::chrono::steady_clock;
    Steady::time_point start_ = Steady::now();
};

// CLOCK_MONOTONIC itself (libstdc++'s steady_clock), not offset to the
// clock's construction: V4L2 drivers stamp frames on it.
class MonotonicClock final : public Clock {
public:
    double now() const override { return std::chrono::duration<double>(Steady::now().time_since_epoch()).count(); }

    void wait_until(double seconds) override {
        std::this_thread::sleep_until(Steady::time_point(std::chrono::duration_cast<Steady::duration>(
            std::chrono::duration<double>(seconds))));
    }

private:
    using Steady = std::chrono::steady_clock;
};

// Time moves only when someone waits, so a simulation runs as fast as the CPU
// allows and gives the same timestamps on every run. Several threads (a sensor
// and the rig) may share one, hence the mutex.
class VirtualClock final : public Clock {
public:
    double now() const override {
        std::lock_guard lock(mutex_);
        return now_;
    }

    void wait_until(double seconds) override {
        std::lock_guard lock(mutex_);
        now_ = std::max(now_, seconds);
    }

    bool passes_on_its_own() const override { return false; }

private:
    mutable std::mutex mutex_;
    double now_ = 0;
};

}  // namespace

std::shared_ptr<Clock> make_real_clock() { return std::make_shared<RealClock>(); }
std::shared_ptr<Clock> make_monotonic_clock() { return std::make_shared<MonotonicClock>(); }
std::shared_ptr<Clock> make_virtual_clock() { return std::make_shared<VirtualClock>(); }

}  // namespace vkfuse

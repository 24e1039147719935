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

private:
    mutable std::mutex mutex_;
    double now_ = 0;
};

}  // namespace

std::shared_ptr<Clock> make_real_clock() { return std::make_shared<RealClock>(); }
std::shared_ptr<Clock> make_virtual_clock() { return std::make_shared<VirtualClock>(); }

}  // namespace vkfuse

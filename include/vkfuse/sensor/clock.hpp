// vkfuse/sensor/clock.hpp - the time a sensor lives in: real for live runs, virtual
// for fast deterministic tests and replays.
#pragma once
#include <memory>

namespace vkfuse {

class Clock {
public:
    virtual ~Clock() = default;
    virtual double now() const = 0;             // seconds since the clock's start
    virtual void wait_until(double seconds) = 0;  // returns once now() >= seconds
    // True (the default) when time passes on its own, so a thread held back
    // misses what happens meanwhile; false for a virtual clock, whose time
    // waits for its threads (and whose runs are therefore deterministic).
    virtual bool passes_on_its_own() const { return true; }
};

// std::chrono::steady_clock from construction; wait_until sleeps.
std::shared_ptr<Clock> make_real_clock();
// CLOCK_MONOTONIC in seconds since boot: the clock V4L2 drivers stamp frames
// on, so a live camera's timestamps and LED requests share it.
std::shared_ptr<Clock> make_monotonic_clock();
// Starts at 0; wait_until jumps forward instantly (never backwards). Thread-safe.
std::shared_ptr<Clock> make_virtual_clock();

}  // namespace vkfuse

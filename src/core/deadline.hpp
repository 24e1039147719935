// core/deadline.hpp - a time point some seconds from now, without overflow.
#pragma once
#include <chrono>
#include <cmath>

namespace vkfuse {

// start + seconds on Clock, saturated: a duration beyond what Clock's integer
// ticks can hold from start (std::chrono::steady_clock counts int64
// nanoseconds, about 292 years) means "never" and gives the latest time point
// Clock can represent, instead of the wrapped, past one a plain duration_cast
// gives (which would make a wait end at once). NaN and non-positive seconds
// give start.
template <class Clock>
typename Clock::time_point deadline_after(typename Clock::time_point start, double seconds) {
    using TimePoint = typename Clock::time_point;
    using Duration = typename Clock::duration;
    if (!(seconds > 0)) return start;
    const Duration headroom = TimePoint::max() - start;
    const double headroom_s = std::chrono::duration<double>(headroom).count();
    // Compare in double, with a margin for its rounding near the int64 limit.
    if (!(seconds < headroom_s * 0.5)) return TimePoint::max();
    return start + std::chrono::duration_cast<Duration>(std::chrono::duration<double>(seconds));
}

}  // namespace vkfuse

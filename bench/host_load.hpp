// How busy the host is: timings taken while other processes run are slower,
// and a report should say so rather than let the numbers mislead.
#pragma once

namespace vkfuse::bench {

// The 1-minute load average from /proc/loadavg, or -1 where it cannot be read.
double load_average();

}  // namespace vkfuse::bench

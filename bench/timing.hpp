// Timing a cycle: warm-up, then timed repeats, summarised as median/min/max.
#pragma once
#include <functional>
#include <vector>

namespace vkfuse::bench {

// Timing a cycle: warm-up, then timed repeats, summarised as median/min/max.

struct RunPolicy {
    int warmup = 2;
    int runs = 20;
    // When may_cap is set (the CPU reference, or a Vulkan device that is itself
    // a CPU) and runs would take longer than cell_seconds, fewer runs are made
    // (never fewer than 3): a 4096x4096 reference cycle takes minutes.
    double cell_seconds = 60;
    bool may_cap = false;
};

struct Timing {
    double median_ms = 0;
    double min_ms = 0;
    double max_ms = 0;
    int runs = 0;
    bool capped = false;  // fewer runs than asked for, by the time budget
};

// Median of values (the mean of the middle two for an even count); 0 if empty.
double median(std::vector<double> values);

// Runs cycle() policy.warmup times, then the timed runs; after_run() follows
// each timed run, outside the timed interval (for reading profiles).
Timing time_cycles(const RunPolicy& policy, const std::function<void()>& cycle,
                   const std::function<void()>& after_run = {});

// How busy the host is: timings taken while other processes run are slower,
// and a report should say so rather than let the numbers mislead.

// The 1-minute load average from /proc/loadavg, or -1 where it cannot be read.
double load_average();

}  // namespace vkfuse::bench

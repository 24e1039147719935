#include "timing.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>

namespace vkfuse::bench {

namespace {

double time_ms(const std::function<void()>& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Runs allowed after a first cycle of first_ms, and whether that is a cap.
int capped_runs(const RunPolicy& p, double first_ms, bool& capped) {
    capped = false;
    if (!p.may_cap || first_ms <= 0) return p.runs;
    const int runs = std::min(p.runs, std::max(3, int(p.cell_seconds * 1000.0 / first_ms)));
    capped = runs < p.runs;
    return runs;
}

}  // namespace

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Timing time_cycles(const RunPolicy& policy, const std::function<void()>& cycle,
                   const std::function<void()>& after_run) {
    std::vector<double> ms;
    Timing t;
    int runs = policy.runs;
    if (policy.warmup > 0) {
        // The first warm-up cycle tells how long one takes; a slow cell skips
        // the remaining warm-ups (their purpose, warm caches, is served).
        runs = capped_runs(policy, time_ms(cycle), t.capped);
        for (int i = 1; i < policy.warmup && !t.capped; ++i) cycle();
    }
    for (int i = 0; i < runs; ++i) {
        ms.push_back(time_ms(cycle));
        if (after_run) after_run();
        if (i == 0 && policy.warmup == 0) runs = capped_runs(policy, ms.front(), t.capped);
    }
    t.runs = int(ms.size());
    t.median_ms = median(ms);
    t.min_ms = *std::min_element(ms.begin(), ms.end());
    t.max_ms = *std::max_element(ms.begin(), ms.end());
    return t;
}

double load_average() {
    std::ifstream in("/proc/loadavg");
    double one_minute = -1;
    if (!(in >> one_minute)) return -1;
    return one_minute;
}

}  // namespace vkfuse::bench

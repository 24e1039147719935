// sensor/realtime_section.hpp - the calling thread under real-time
// scheduling (SCHED_FIFO) for a short section: an LED switch request, whose
// slack (SwitchTiming::clearance) is about a millisecond, less than a busy
// host's scheduler may keep a woken thread waiting. Only the wait for the
// request's moment and the request itself run so; the thread's other work
// (reading frames out, a simulated camera's rendering) stays under the
// normal scheduler, so a slow host can never be starved by it.
#pragma once
#include <string>

namespace vkfuse::sensor {

// Whether this thread may run at SCHED_FIFO priority (1..99): "" if it may
// (or already runs real-time at least that high), else why not ("Operation
// not permitted": no CAP_SYS_NICE and an RLIMIT_RTPRIO below priority).
// Leaves the thread as it found it: one RealtimeSection, tried.
std::string realtime_refusal(int priority);

class RealtimeSection {
public:
    // priority 0: nothing changes. Otherwise the thread runs under SCHED_FIFO
    // at priority until the destructor restores its policy; a refusal leaves
    // it under its own and says why in refusal().
    explicit RealtimeSection(int priority);
    ~RealtimeSection();
    RealtimeSection(const RealtimeSection&) = delete;
    RealtimeSection& operator=(const RealtimeSection&) = delete;
    const std::string& refusal() const { return refusal_; }

private:
    std::string refusal_;
    bool raised_ = false;
    int policy_ = 0;
    int priority_ = 0;  // the thread's own, restored
};

}  // namespace vkfuse::sensor

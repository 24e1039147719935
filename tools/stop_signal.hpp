// stop_signal.hpp - Ctrl-C as a request to stop after the current cycle.
#pragma once
#include <csignal>

namespace vkfuse::cli {

// While alive, SIGINT only sets a flag that the run loop polls between
// cycles; the loop then finishes the cycle in hand and flushes its files. The
// handler resets itself (SA_RESETHAND), so a second Ctrl-C kills at once.
// No self-pipe is needed: the loop never blocks longer than one cycle, which
// the rig bounds by its cycle timeout. One instance at a time.
class StopSignal {
public:
    StopSignal();
    ~StopSignal();
    StopSignal(const StopSignal&) = delete;
    StopSignal& operator=(const StopSignal&) = delete;

    bool requested() const;

private:
    struct sigaction previous_ {};
};

}  // namespace vkfuse::cli

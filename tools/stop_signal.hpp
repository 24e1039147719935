// stop_signal.hpp - Ctrl-C or SIGTERM as a request to stop after the current cycle.
#pragma once
#include <csignal>

namespace vkfuse::cli {

// While alive, SIGINT and SIGTERM (what `timeout`, systemd and docker send)
// only set a flag that the run loop polls between cycles; the loop then
// finishes the cycle in hand and writes its files (a --record's manifest
// too). Each handler resets itself (SA_RESETHAND), so a second signal of
// the same kind kills at once.
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
    struct sigaction previous_int_ {}, previous_term_ {};
};

}  // namespace vkfuse::cli

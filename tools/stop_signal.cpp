#include "stop_signal.hpp"

namespace vkfuse::cli {
namespace {

// The one piece of global mutable state: a signal handler can reach nothing
// else, and a volatile sig_atomic_t is what it may safely write.
volatile std::sig_atomic_t g_stop_requested = 0;

void on_sigint(int) { g_stop_requested = 1; }

}  // namespace

StopSignal::StopSignal() {
    g_stop_requested = 0;
    struct sigaction action {};
    action.sa_handler = on_sigint;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, &previous_);
}

StopSignal::~StopSignal() { sigaction(SIGINT, &previous_, nullptr); }

bool StopSignal::requested() const { return g_stop_requested != 0; }

}  // namespace vkfuse::cli

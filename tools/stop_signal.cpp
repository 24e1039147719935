#include "stop_signal.hpp"

namespace vkfuse::cli {
namespace {

// The one piece of global mutable state: a signal handler can reach nothing
// else, and a volatile sig_atomic_t is what it may safely write.
volatile std::sig_atomic_t g_stop_requested = 0;

void on_stop_signal(int) { g_stop_requested = 1; }

}  // namespace

StopSignal::StopSignal() {
    g_stop_requested = 0;
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, &previous_int_);
    sigaction(SIGTERM, &action, &previous_term_);
}

StopSignal::~StopSignal() {
    sigaction(SIGTERM, &previous_term_, nullptr);
    sigaction(SIGINT, &previous_int_, nullptr);
}

bool StopSignal::requested() const { return g_stop_requested != 0; }

}  // namespace vkfuse::cli

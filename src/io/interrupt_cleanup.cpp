#include "io/interrupt_cleanup.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace vkfuse::io {
namespace {

// A slot is claimed (Free -> Filling), filled, then published (Ready); the
// handler only reads Ready slots. Only lock-free atomics and plain arrays:
// nothing here may allocate or lock, the handler runs between any two
// instructions of the writer.
enum SlotState : int { Free, Filling, Ready };
constexpr int kSlots = 16;
constexpr std::size_t kNameBytes = 64;

struct Slot {
    std::atomic<int> state{Free};
    int dirfd = -1;
    char name[kNameBytes] = {};
};
static_assert(std::atomic<int>::is_always_lock_free);

Slot g_slots[kSlots];

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[sizeof kSignals / sizeof kSignals[0]];
std::atomic<bool> g_installed{false};

void on_signal(int sig) {
    const int saved_errno = errno;
    unlink_registered_temporaries();
    for (std::size_t i = 0; i < sizeof kSignals / sizeof kSignals[0]; ++i)
        if (kSignals[i] == sig) ::sigaction(sig, &g_previous[i], nullptr);
    // The signal is blocked while its handler runs: raised now, it is
    // delivered to the previous disposition (the default: termination) as
    // soon as this handler returns.
    ::raise(sig);
    errno = saved_errno;
}

}  // namespace

void unlink_registered_temporaries() {
    for (Slot& s : g_slots)
        if (s.state.load(std::memory_order_acquire) == Ready) ::unlinkat(s.dirfd, s.name, 0);
}

int register_temporary(int dirfd, std::string_view name) {
    if (name.empty() || name.size() >= kNameBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = Free;
        if (!g_slots[i].state.compare_exchange_strong(expected, Filling, std::memory_order_acq_rel)) continue;
        g_slots[i].dirfd = dirfd;
        std::memcpy(g_slots[i].name, name.data(), name.size());
        g_slots[i].name[name.size()] = '\0';
        g_slots[i].state.store(Ready, std::memory_order_release);
        return i;
    }
    return -1;
}

void release_temporary(int slot) {
    if (slot >= 0 && slot < kSlots) g_slots[slot].state.store(Free, std::memory_order_release);
}

void install_interrupt_cleanup() {
    if (g_installed.exchange(true)) return;
    for (std::size_t i = 0; i < sizeof kSignals / sizeof kSignals[0]; ++i) {
        struct sigaction current {};
        if (::sigaction(kSignals[i], nullptr, &current) != 0) continue;
        if (current.sa_handler != SIG_DFL || (current.sa_flags & SA_SIGINFO)) continue;  // ignored or handled
        struct sigaction action {};
        action.sa_handler = on_signal;
        sigemptyset(&action.sa_mask);
        action.sa_flags = SA_RESTART;
        ::sigaction(kSignals[i], &action, &g_previous[i]);
    }
    ::signal(SIGXFSZ, SIG_IGN);
}

}  // namespace vkfuse::io

// io/interrupt_cleanup.hpp - named temporaries do not outlive a SIGINT/SIGTERM.
//
// write_atomically stages a file under a hidden name only where the file
// system has no O_TMPFILE (an unnamed file needs no cleanup: it vanishes with
// the process), and for the instant between linking the finished file in and
// renaming it. Those names are kept in a fixed table that a signal handler
// can walk without allocating or locking; the handler unlinks them, puts the
// previous disposition back and raises the signal again, so the process still
// dies of it (exit status 128 + signal for the shell).
#pragma once
#include <string_view>

namespace vkfuse::io {

// Installs the handler for SIGINT, SIGTERM and SIGHUP, each only where its
// disposition is still the default: a signal the caller ignores (nohup) stays
// ignored, and a command with its own handlers (vkfuse run's StopSignal, which
// stops cleanly and lets every writer clean up itself) is left alone; calling
// this after such handlers are installed changes nothing. Also ignores
// SIGXFSZ, so a file-size limit (ulimit -f) makes write(2) fail with EFBIG,
// which the writers report naming the file, instead of killing the process
// with a temporary left behind. Idempotent; not thread-safe against itself.
void install_interrupt_cleanup();

// The table the handler walks (used by write_atomically). register_temporary
// returns a slot, or -1 when the table is full or name is too long (the file
// is then not cleaned up on a signal, nothing else changes); dirfd must stay
// open until release_temporary(slot).
int register_temporary(int dirfd, std::string_view name);
void release_temporary(int slot);

// What the handler does, callable from tests: unlinks every registered name.
void unlink_registered_temporaries();

}  // namespace vkfuse::io

#pragma once
// Ctrl-C for long work. The CLI installs the handlers; the first SIGINT or SIGTERM only asks the
// work to stop, and the work stops at its next progress step (Progress::Advance throws
// Interrupted there, on the thread that made the Progress). The exception unwinds through the
// outputs' AtomicFile and AtomicDirectory, which remove what they had not committed, so nothing
// half-written is left. A second signal ends the process at once.

#include "simtree/core/error.h"

namespace simtree {

// What a stopped verb throws; the CLI exits 130 (128 + SIGINT) for it, as shells expect.
class Interrupted : public Error {
 public:
  Interrupted()
      : Error("interrupted: stopped before the end, no output written or replaced", 130) {}
};

// SIGINT and SIGTERM set the request (the first time) or end the process (the second).
void InstallInterruptHandlers();

bool InterruptRequested();

// Throws Interrupted when a stop was requested.
void ThrowIfInterrupted();

// Sets or clears the request as a signal would (tests, and work that stops itself).
void SetInterruptRequested(bool requested);

}  // namespace simtree

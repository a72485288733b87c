#include "simtree/core/interrupt.h"

#include <atomic>
#include <csignal>

namespace simtree {
namespace {

// Lock-free, so the signal handler may set it.
std::atomic<bool> g_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void OnInterruptSignal(int signal_number) {
  if (g_requested.exchange(true)) {
    // The second signal: the user means it. Default action, at once.
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
  }
}

}  // namespace

void InstallInterruptHandlers() {
  struct sigaction action = {};
  action.sa_handler = OnInterruptSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // blocking reads resume; the work checks at its next step
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool InterruptRequested() { return g_requested.load(std::memory_order_relaxed); }

void ThrowIfInterrupted() {
  if (InterruptRequested()) throw Interrupted();
}

void SetInterruptRequested(bool requested) { g_requested = requested; }

}  // namespace simtree

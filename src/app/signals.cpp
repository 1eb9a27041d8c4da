#include "app/signals.h"

#include <unistd.h>

#include <atomic>

namespace pt {
namespace {

// The only process-wide state of the program: what a signal handler may touch.
std::atomic<int> g_received{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal flag must be lock-free");

extern "C" void on_signal(int signal_number) {
  int expected = 0;
  // Second signal: abort now (_exit is async-signal-safe; nothing is flushed).
  if (!g_received.compare_exchange_strong(expected, signal_number)) ::_exit(exit_status_for_signal(signal_number));
}

}  // namespace

SignalCancellation::SignalCancellation() {
  g_received.store(0);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &sa, &old_int_);
  ::sigaction(SIGTERM, &sa, &old_term_);
}

SignalCancellation::~SignalCancellation() {
  ::sigaction(SIGINT, &old_int_, nullptr);
  ::sigaction(SIGTERM, &old_term_, nullptr);
}

int SignalCancellation::received() const { return g_received.load(std::memory_order_relaxed); }

}  // namespace pt

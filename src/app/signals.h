// SIGINT/SIGTERM handling for the command line (docs/cli.md): the first signal
// asks the render to stop (RenderMonitor::cancelled polls it before each tile),
// after which the driver writes what it has, marked partial, and exits with
// 128 + the signal number (130 for SIGINT, 143 for SIGTERM, as shells report
// them). A second signal ends the process at once with the same status.
//
// A signal handler can only reach static storage, so the flag is the one
// process-wide variable of the program; it is a lock-free std::atomic<int>
// (async-signal-safe), and the handler does nothing else (no allocation, no I/O).
#pragma once

#include <signal.h>

namespace pt {

class SignalCancellation {
 public:
  // Installs the handlers (sigaction) for SIGINT and SIGTERM; the destructor
  // restores the previous ones. One instance at a time.
  SignalCancellation();
  ~SignalCancellation();
  SignalCancellation(const SignalCancellation&) = delete;
  SignalCancellation& operator=(const SignalCancellation&) = delete;

  // The first signal received since construction, or 0.
  int received() const;
  bool cancelled() const { return received() != 0; }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

// The exit status for a render stopped by `signal_number` (128 + it).
constexpr int exit_status_for_signal(int signal_number) { return 128 + signal_number; }

}  // namespace pt

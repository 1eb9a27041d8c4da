// Wall-clock time for phase timings and benchmarks: the steady clock, and the
// seconds elapsed since a point of it; and the process's CPU time, for
// benchmarks on a machine shared with other jobs.
#pragma once

#include <time.h>

#include <chrono>

namespace pt {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU time of the whole process so far, every thread: it counts the time the
// process ran, not the time it waited for a core.
inline double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace pt

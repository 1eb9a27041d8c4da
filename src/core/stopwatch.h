// Wall-clock time for phase timings and benchmarks: the steady clock, and the
// seconds elapsed since a point of it.
#pragma once

#include <chrono>

namespace pt {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace pt

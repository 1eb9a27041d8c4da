// Test-only: the invariant check of the fuzzing harnesses. A violated
// invariant prints what broke and aborts, which libFuzzer (and the replaying
// test, as a crash) reports with the input that caused it.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace pt::fuzz {

inline void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz invariant violated: %s\n", what);
  std::abort();
}

}  // namespace pt::fuzz

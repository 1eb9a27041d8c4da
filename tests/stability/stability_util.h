// Test-only helpers for the stability catalogue: random picks and log-uniform
// magnitudes on top of tests/geometry/test_util.h.
#pragma once

#include <cmath>
#include <cstddef>

#include "../geometry/test_util.h"

namespace pt::test {

// A uniformly chosen index in [0, n), n > 0.
inline std::size_t pick(Rng& rng, std::size_t n) {
  const auto i = static_cast<std::size_t>(rng.uniform() * static_cast<float>(n));
  return i < n ? i : n - 1;
}

// 10^U(lo_exp, hi_exp): magnitudes spread evenly over the decades.
inline float log_uniform(Rng& rng, float lo_exp, float hi_exp) {
  return std::pow(10.0f, rng.uniform(lo_exp, hi_exp));
}

// A point whose coordinates are each +-10^U(lo_exp, hi_exp).
inline Vec3f log_uniform_point(Rng& rng, float lo_exp, float hi_exp) {
  Vec3f p;
  for (int i = 0; i < 3; ++i) p[i] = (rng.uniform() < 0.5f ? -1.0f : 1.0f) * log_uniform(rng, lo_exp, hi_exp);
  return p;
}

}  // namespace pt::test

#include "throughput.h"

#include <algorithm>

namespace pt::bench {

Measured summarize(std::vector<double> samples) {
  Measured m;
  if (samples.empty()) return m;
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  m.median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  m.min = samples.front();
  m.max = samples.back();
  return m;
}

}  // namespace pt::bench

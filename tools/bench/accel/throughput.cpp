#include "throughput.h"

#include <algorithm>
#include <atomic>
#include <chrono>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/parallel.h"

namespace pt::bench {

Pass trace_pass(const Accelerator& accel, const std::vector<Ray>& rays, Query query, WorkerPool& pool) {
  std::atomic<std::size_t> hits{0};
  const auto start = std::chrono::steady_clock::now();
  pool.run([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
      std::size_t local = 0;
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        if (query == Query::Any) {
          local += accel.occluded(rays[i]) ? 1 : 0;
        } else {
          Hit hit;
          local += accel.intersect(rays[i], hit) ? 1 : 0;
        }
      }
      hits += local;
    });
  });
  const auto stop = std::chrono::steady_clock::now();
  return Pass{std::chrono::duration<double>(stop - start).count(), hits.load()};
}

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

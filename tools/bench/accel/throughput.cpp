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

WorkPerRay count_work(const Accelerator& accel, const std::vector<Ray>& rays, WorkerPool& pool) {
  WorkPerRay w;
  if (!accel.counts_traversal() || rays.empty()) return w;
  std::atomic<uint64_t> nodes{0}, prims{0};
  pool.run([&] {
    const tbb::blocked_range<std::size_t> all(0, rays.size(), 256);
    tbb::parallel_for(all, [&](const tbb::blocked_range<std::size_t>& r) {
      uint64_t n = 0, p = 0;
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        TraversalCounters c;
        Hit hit;
        accel.intersect_counted(rays[i], hit, c);
        n += c.nodes;
        p += c.primitives;
      }
      nodes += n;
      prims += p;
    });
  });
  const auto count = static_cast<double>(rays.size());
  w.nodes = static_cast<double>(nodes.load()) / count;
  w.prims = static_cast<double>(prims.load()) / count;
  return w;
}

}  // namespace pt::bench

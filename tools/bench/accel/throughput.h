// Timing of ray queries: one pass traces a whole ray set in parallel inside
// the worker pool (chunks of 256 rays per task), and repetitions are reduced
// to their median, minimum and maximum.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "accel/accelerator.h"
#include "core/parallel.h"
#include "core/stopwatch.h"

namespace pt::bench {

enum class Query { Nearest, Any };

struct Pass {
  double seconds = 0;      // wall-clock time
  double cpu_seconds = 0;  // CPU time of the whole process (every thread) over the same interval
  std::size_t hits = 0;    // rays that found a hit (a check that both backends did the same work)
  float checksum = 0.0f;   // of the hit records read (unused: it keeps them from being optimised away)
};

// A is Accelerator (a virtual call per ray, as the renderer makes) or a final
// class called directly (the bare-Embree yardstick, embree_reference.h).
template <class A>
Pass trace_pass(const A& accel, const std::vector<Ray>& rays, Query query, WorkerPool& pool) {
  std::atomic<std::size_t> hits{0};
  std::atomic<float> sink{0.0f};
  const double cpu_start = process_cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  pool.run([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
      std::size_t local = 0;
      float checksum = 0.0f;
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        if (query == Query::Any) {
          local += accel.occluded(rays[i]) ? 1 : 0;
        } else {
          Hit hit;
          if (accel.intersect(rays[i], hit)) {
            ++local;
            // Read the hit record, as any caller does: an accelerator inlined
            // here (the bare-Embree yardstick) may not skip producing it.
            checksum += hit.t + hit.uv.x + static_cast<float>(hit.prim + hit.shape);
          }
        }
      }
      hits += local;
      sink += checksum;
    });
  });
  const auto stop = std::chrono::steady_clock::now();
  return Pass{std::chrono::duration<double>(stop - start).count(), process_cpu_seconds() - cpu_start, hits.load(),
              sink.load()};
}

struct Measured {
  double median = 0, min = 0, max = 0;
  // (max - min) / median: the spread of the repetitions, stated with every figure.
  double spread() const { return median > 0 ? (max - min) / median : 0.0; }
};

Measured summarize(std::vector<double> samples);

// The work an accelerator that counts_traversal() does per ray of a set,
// traced as nearest-hit queries (intersect_counted): mean nodes whose children
// were tested and mean primitives tested. Zero for a backend that cannot count.
struct WorkPerRay {
  double nodes = 0, prims = 0;
};
WorkPerRay count_work(const Accelerator& accel, const std::vector<Ray>& rays, WorkerPool& pool);

}  // namespace pt::bench

// Timing of ray queries: one pass traces a whole ray set in parallel inside
// the worker pool (chunks of 256 rays per task), and repetitions are reduced
// to their median, minimum and maximum.
#pragma once

#include <cstddef>
#include <vector>

#include "accel/accelerator.h"

namespace pt {
class WorkerPool;
}

namespace pt::bench {

enum class Query { Nearest, Any };

struct Pass {
  double seconds = 0;
  std::size_t hits = 0;  // rays that found a hit (a check that both backends did the same work)
};

Pass trace_pass(const Accelerator& accel, const std::vector<Ray>& rays, Query query, WorkerPool& pool);

struct Measured {
  double median = 0, min = 0, max = 0;
  // (max - min) / median: the spread of the repetitions, stated with every figure.
  double spread() const { return median > 0 ? (max - min) / median : 0.0; }
};

Measured summarize(std::vector<double> samples);

}  // namespace pt::bench

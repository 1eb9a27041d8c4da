// The renderer's single TBB arena. Everything parallel (accel builds, rendering)
// runs inside WorkerPool::run so that `--threads N` bounds all work, and every
// worker thread that enters the arena gets flush-to-zero and denormals-are-zero
// set (required by Embree, and keeps denormal arithmetic off the slow path).
#pragma once

#include <memory>

#include "core/function_ref.h"

namespace pt {

// Sets FTZ and DAZ in the calling thread's MXCSR.
void enable_flush_to_zero();
// True if both FTZ and DAZ are set in the calling thread.
bool flush_to_zero_enabled();

class WorkerPool {
 public:
  // threads <= 0: all hardware threads.
  explicit WorkerPool(int threads = 0);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const;

  // Runs f() inside the arena (blocking). Parallel algorithms called from f
  // (tbb::parallel_for etc.) use only this arena's threads.
  void run(FunctionRef<void()> f);

 private:

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pt

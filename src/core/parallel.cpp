#include "core/parallel.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <thread>

#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>

namespace pt {

void enable_flush_to_zero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

bool flush_to_zero_enabled() {
  return _MM_GET_FLUSH_ZERO_MODE() == _MM_FLUSH_ZERO_ON &&
         _MM_GET_DENORMALS_ZERO_MODE() == _MM_DENORMALS_ZERO_ON;
}

namespace {
// Sets FTZ/DAZ in every thread as it joins the arena.
class FtzObserver : public tbb::task_scheduler_observer {
 public:
  explicit FtzObserver(tbb::task_arena& arena) : tbb::task_scheduler_observer(arena) { observe(true); }
  ~FtzObserver() override { observe(false); }
  void on_scheduler_entry(bool /*is_worker*/) override { enable_flush_to_zero(); }
};
}  // namespace

struct WorkerPool::Impl {
  explicit Impl(int n) : arena(n), observer(arena) {
    // oneTBB captures the floating-point settings of the thread that initialises
    // an arena and restores them around every task it runs there, which would
    // undo the observer's setting. So initialise it with FTZ/DAZ on, then give
    // the calling thread its own settings back.
    const unsigned int saved = _mm_getcsr();
    enable_flush_to_zero();
    arena.initialize();
    _mm_setcsr(saved);
  }
  tbb::task_arena arena;
  FtzObserver observer;  // threads entering the arena outside tasks
};

static int resolve_threads(int threads) {
  if (threads > 0) return threads;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(hw) : 1;
}

WorkerPool::WorkerPool(int threads) : impl_(std::make_unique<Impl>(resolve_threads(threads))) {}
WorkerPool::~WorkerPool() = default;

int WorkerPool::threads() const { return impl_->arena.max_concurrency(); }

void WorkerPool::run_impl(FunctionRef f) {
  impl_->arena.execute([&] {
    // The calling thread runs f itself: give it FTZ/DAZ too, and its own
    // settings back afterwards.
    const unsigned int saved = _mm_getcsr();
    enable_flush_to_zero();
    f.call(f.obj);
    _mm_setcsr(saved);
  });
}

}  // namespace pt

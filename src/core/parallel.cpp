#include "core/parallel.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <optional>
#include <thread>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>
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

// TBB caps its workers at the hardware concurrency unless told otherwise:
// --threads N above the core count must still get N threads (thread-count
// determinism tests rely on it). Only ever raises the cap: TBB applies the
// smallest of all live limits, process-wide. Must exist before the arena
// initialises (the observer initialises it).
std::optional<tbb::global_control> raise_parallelism_cap(int n) {
  const auto cap = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  if (static_cast<std::size_t>(n) <= cap) return std::nullopt;
  return std::make_optional<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 static_cast<std::size_t>(n));
}

struct WorkerPool::Impl {
  explicit Impl(int n) : allow(raise_parallelism_cap(n)), arena(n), observer(arena) {}
  std::optional<tbb::global_control> allow;
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

void WorkerPool::run(FunctionRef<void()> f) {
  const unsigned int saved = _mm_getcsr();
  impl_->arena.execute([&] {
    // oneTBB runs each task with the floating-point settings of its task group
    // context, which a nested parallel algorithm inherits from its parent
    // context. So f runs in a task group whose context captured FTZ/DAZ: every
    // task under it, on any thread, gets them. The caller's settings are
    // restored afterwards (outside the arena: TBB may set them on the way out).
    enable_flush_to_zero();
    tbb::task_group_context context;
    context.capture_fp_settings();
    tbb::task_group group(context);
    group.run_and_wait([&] { f(); });
  });
  _mm_setcsr(saved);
}

}  // namespace pt

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <thread>

#include <tbb/parallel_for.h>

#include "core/parallel.h"

namespace pt {
namespace {

TEST(WorkerPool, HonoursThreadCount) {
  WorkerPool pool(2);
  EXPECT_EQ(pool.threads(), 2);
  WorkerPool one(1);
  std::mutex m;
  std::set<std::thread::id> ids;
  one.run([&] {
    tbb::parallel_for(0, 1000, [&](int) {
      std::lock_guard<std::mutex> lock(m);
      ids.insert(std::this_thread::get_id());
    });
  });
  EXPECT_EQ(ids.size(), 1u);
}

TEST(WorkerPool, EveryWorkerHasFlushToZero) {
  WorkerPool pool(4);
  std::atomic<int> without{0};
  std::atomic<int> total{0};
  pool.run([&] {
    tbb::parallel_for(0, 20000, [&](int) {
      ++total;
      if (!flush_to_zero_enabled()) ++without;
    });
  });
  EXPECT_EQ(total.load(), 20000);
  EXPECT_EQ(without.load(), 0);
}

TEST(WorkerPool, DenormalsFlushInsideArena) {
  WorkerPool pool(2);
  volatile float tiny = 1e-39f;  // a denormal
  volatile float half = 0.5f;    // volatile: no constant folding
  volatile float result = 1.0f;
  pool.run([&] { result = tiny * half; });
  EXPECT_EQ(result, 0.0f);  // DAZ reads the input as zero (and FTZ would flush the output)
  EXPECT_NE(tiny * half, 0.0f);  // outside the pool: ordinary IEEE arithmetic
}

}  // namespace
}  // namespace pt

namespace pt {
namespace {

TEST(WorkerPool, CallerKeepsItsOwnFloatingPointSettings) {
  const bool before = flush_to_zero_enabled();
  WorkerPool pool(2);
  pool.run([] {});
  EXPECT_EQ(flush_to_zero_enabled(), before);
}

}  // namespace
}  // namespace pt

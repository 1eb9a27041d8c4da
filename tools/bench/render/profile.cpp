// The traversal share: every ray of one render is recorded (per worker slot,
// in the order it was cast), then replayed through the accelerator alone with
// the same number of threads, each slot's rays by one task. The replay's time
// is the time the render spent in traversal; the rest of the render's time is
// shading (camera rays, BSDFs, lights, sampling, film). The replay sees the
// rays in their original order, so it keeps their coherence, but not the
// cache traffic of the shading between them, so the share is a lower bound.
#include <memory>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "measurements.h"

namespace pt::bench {

namespace {

struct RecordedRay {
  Ray ray;
  bool shadow;
};

class RecordingAccelerator final : public Accelerator {
 public:
  RecordingAccelerator(const Accelerator& inner, int slots) : inner_(inner), logs_(static_cast<std::size_t>(slots)) {}

  bool intersect(const Ray& ray, Hit& hit) const override {
    log().push_back({ray, false});
    return inner_.intersect(ray, hit);
  }
  bool occluded(const Ray& ray) const override {
    log().push_back({ray, true});
    return inner_.occluded(ray);
  }
  Bounds3f bounds() const override { return inner_.bounds(); }
  AccelStats stats() const override { return inner_.stats(); }

  std::vector<std::vector<RecordedRay>>& logs() { return logs_; }

 private:
  // Each worker slot of the arena appends to a log of its own.
  std::vector<RecordedRay>& log() const {
    const int slot = tbb::this_task_arena::current_thread_index();
    return logs_[static_cast<std::size_t>(slot) % logs_.size()];
  }

  const Accelerator& inner_;
  mutable std::vector<std::vector<RecordedRay>> logs_;
};

}  // namespace

Profile profile(LoadedScene& s, WorkerPool& pool, int spp, uint64_t seed) {
  Profile out;
  out.render_seconds = throughput(s, pool, spp, seed).seconds;

  std::unique_ptr<Accelerator> inner = std::move(s.scene->accel);
  auto recorder = std::make_unique<RecordingAccelerator>(*inner, pool.threads());
  RecordingAccelerator* rec = recorder.get();
  s.scene->accel = std::move(recorder);
  throughput(s, pool, spp, seed);
  std::vector<std::vector<RecordedRay>> logs = std::move(rec->logs());
  s.scene->accel = std::move(inner);

  for (const auto& log : logs) {
    out.rays += log.size();
    for (const RecordedRay& r : log) out.shadow_rays += r.shadow;
  }
  const Accelerator& accel = *s.scene->accel;
  std::vector<int> sink(logs.size(), 0);
  const auto t = Clock::now();
  pool.run([&] {
    tbb::parallel_for(std::size_t(0), logs.size(), [&](std::size_t i) {
      int hits = 0;
      Hit hit;
      for (const RecordedRay& r : logs[i]) hits += r.shadow ? accel.occluded(r.ray) : accel.intersect(r.ray, hit);
      sink[i] = hits;
    });
  });
  out.traversal_seconds = seconds_since(t);
  return out;
}

}  // namespace pt::bench

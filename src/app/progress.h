// Render progress for the command line (docs/cli.md): the RenderMonitor the
// driver hands to the integrator. It counts finished pixel samples (camera
// paths; one atomic add per 16x16 tile, so its cost is negligible), asks the
// signal flag whether to stop, and a display thread prints either a bar
// (percentage, ETA, samples per second) redrawn in place when stderr is a
// terminal, or one plain line every `interval` seconds when it is not.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <iosfwd>
#include <mutex>
#include <string>
#include <thread>

#include "render/integrators/integrator.h"

namespace pt {

class SignalCancellation;

enum class ProgressStyle { None, Bar, Lines };

struct ProgressSettings {
  ProgressStyle style = ProgressStyle::None;
  double interval_s = 10.0;      // Lines: seconds between lines (the bar redraws 4 times a second)
  int64_t pixels = 0;            // width * height
  int target_spp = 0;            // 0: no sample target (time budget only)
  double time_budget_s = 0.0;    // 0: none
};

// One progress snapshot, formatted by the display thread (exposed for tests).
struct ProgressSnapshot {
  double elapsed_s = 0;
  int64_t samples = 0;      // pixel samples finished
  int spp_done = 0;         // complete passes
  double fraction = 0;      // [0, 1]
  double eta_s = -1;        // < 0: unknown
  double samples_per_s = 0;
  double rays_per_s = 0;
};

ProgressSnapshot make_snapshot(const ProgressSettings& settings, double elapsed_s, int64_t samples, int spp_done,
                               int64_t rays = 0);
std::string format_progress_bar(const ProgressSnapshot& s, int width = 30);
std::string format_progress_line(const ProgressSnapshot& s);

class ProgressMonitor : public RenderMonitor {
 public:
  // `signals` may be null (never cancelled); `out` is where progress goes (stderr).
  ProgressMonitor(const ProgressSettings& settings, const SignalCancellation* signals, std::ostream& out);
  ~ProgressMonitor() override;  // stops the display thread

  bool cancelled() const override;
  void tile_done(int64_t pixel_samples, int64_t rays) override {
    samples_.fetch_add(pixel_samples, std::memory_order_relaxed);
    rays_.fetch_add(rays, std::memory_order_relaxed);
  }

  // Starts the clock and the display thread (if any style is set).
  void start();
  // Stops the display thread; the bar ends with a newline.
  void stop();
  void set_spp_done(int spp) { spp_done_.store(spp, std::memory_order_relaxed); }
  int64_t samples() const { return samples_.load(std::memory_order_relaxed); }
  int64_t rays() const { return rays_.load(std::memory_order_relaxed); }

 private:
  void display_loop();
  ProgressSnapshot snapshot() const;

  ProgressSettings settings_;
  const SignalCancellation* signals_;
  std::ostream& out_;
  std::atomic<int64_t> samples_{0};
  std::atomic<int64_t> rays_{0};
  std::atomic<int> spp_done_{0};
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace pt

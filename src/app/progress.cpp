#include "app/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "app/signals.h"
#include "core/stopwatch.h"

namespace pt {
namespace {

std::string duration_text(double s) {
  if (s < 0 || !std::isfinite(s)) return "--:--";
  const long total = std::lround(s);
  char buf[32];
  if (total >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", total / 60, total % 60);
  return buf;
}

std::string rate_text(double per_s, const char* unit) {
  char buf[32];
  if (per_s >= 1e6)
    std::snprintf(buf, sizeof buf, "%.2f M", per_s / 1e6);
  else if (per_s >= 1e3)
    std::snprintf(buf, sizeof buf, "%.1f k", per_s / 1e3);
  else
    std::snprintf(buf, sizeof buf, "%.0f ", per_s);
  return std::string(buf) + unit;
}

}  // namespace

// "1.73 M samples/s, 8.71 M rays/s" (rays only when counted).
static std::string rates_text(const ProgressSnapshot& s) {
  std::string text = rate_text(s.samples_per_s, "samples/s");
  if (s.rays_per_s > 0) text += ", " + rate_text(s.rays_per_s, "rays/s");
  return text;
}

ProgressSnapshot make_snapshot(const ProgressSettings& st, double elapsed_s, int64_t samples, int spp_done,
                               int64_t rays) {
  ProgressSnapshot s;
  s.elapsed_s = elapsed_s;
  s.samples = samples;
  s.spp_done = spp_done;
  s.samples_per_s = elapsed_s > 0 ? static_cast<double>(samples) / elapsed_s : 0.0;
  s.rays_per_s = elapsed_s > 0 ? static_cast<double>(rays) / elapsed_s : 0.0;
  double fraction = 0, eta = -1;
  if (st.target_spp > 0 && st.pixels > 0) {
    const double total = static_cast<double>(st.pixels) * st.target_spp;
    fraction = std::min(1.0, static_cast<double>(samples) / total);
    if (s.samples_per_s > 0) eta = std::max(0.0, (total - static_cast<double>(samples)) / s.samples_per_s);
  }
  if (st.time_budget_s > 0) {
    const double by_time = std::min(1.0, elapsed_s / st.time_budget_s);
    const double left = std::max(0.0, st.time_budget_s - elapsed_s);
    fraction = std::max(fraction, by_time);
    eta = eta < 0 ? left : std::min(eta, left);
  }
  s.fraction = fraction;
  s.eta_s = eta;
  return s;
}

std::string format_progress_bar(const ProgressSnapshot& s, int width) {
  const int filled = static_cast<int>(s.fraction * width);
  std::string bar(static_cast<std::size_t>(width) + 2, '.');
  bar.front() = '[';
  bar.back() = ']';
  std::fill(bar.begin() + 1, bar.begin() + 1 + filled, '#');
  char buf[64];
  std::snprintf(buf, sizeof buf, " %5.1f%%  ETA %s  ", s.fraction * 100.0, duration_text(s.eta_s).c_str());
  return bar + buf + rates_text(s) + "  " + std::to_string(s.spp_done) + " spp done";
}

std::string format_progress_line(const ProgressSnapshot& s) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "progress: %.1f%%, elapsed %s, ETA %s, ", s.fraction * 100.0,
                duration_text(s.elapsed_s).c_str(), duration_text(s.eta_s).c_str());
  return buf + rates_text(s) + ", " + std::to_string(s.spp_done) + " spp done";
}

ProgressMonitor::ProgressMonitor(const ProgressSettings& settings, const SignalCancellation* signals,
                                 std::ostream& out)
    : settings_(settings), signals_(signals), out_(out), start_(std::chrono::steady_clock::now()) {}

ProgressMonitor::~ProgressMonitor() { stop(); }

bool ProgressMonitor::cancelled() const { return signals_ != nullptr && signals_->cancelled(); }

void ProgressMonitor::start() {
  start_ = std::chrono::steady_clock::now();
  if (settings_.style == ProgressStyle::None || thread_.joinable()) return;
  stopping_ = false;
  thread_ = std::thread([this] { display_loop(); });
}

void ProgressMonitor::stop() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (settings_.style == ProgressStyle::Bar) out_ << '\r' << format_progress_bar(snapshot()) << '\n' << std::flush;
}

ProgressSnapshot ProgressMonitor::snapshot() const {
  const double elapsed = seconds_since(start_);
  return make_snapshot(settings_, elapsed, samples(), spp_done_.load(std::memory_order_relaxed), rays());
}

void ProgressMonitor::display_loop() {
  const bool bar = settings_.style == ProgressStyle::Bar;
  const auto period = std::chrono::duration<double>(bar ? 0.25 : std::max(0.05, settings_.interval_s));
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, period, [this] { return stopping_; })) {
    if (bar)
      out_ << '\r' << format_progress_bar(snapshot()) << std::flush;
    else
      out_ << format_progress_line(snapshot()) << '\n' << std::flush;
  }
}

}  // namespace pt

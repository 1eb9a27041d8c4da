#include "app/render_driver.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/stopwatch.h"
#include "render/film/film.h"

namespace pt {
namespace {

// Under a time budget, a pass is aimed at no more than this share of the time
// left, so a misestimate of one pass cannot overshoot by much, and never at
// less than about this long (no tiny passes once the speed is known).
// The last pass is planned to end at kSafety of the budget: the speed varies
// (other processes, the scene's harder parts), and a pass, once started,
// completes.
constexpr double kPassShareOfTimeLeft = 0.25;
constexpr double kMinPassSeconds = 0.1;
constexpr double kSafety = 0.9;
// ... and at most about this long: a signal is only seen between tiles, and
// checkpoints only between passes, so long passes would delay both.
constexpr double kMaxPassSeconds = 4.0;
// Default pass size under a time budget when passes must be equal (jittered).
constexpr int kDefaultEqualPass = 4;

int largest_divisor_at_most(int n, int limit) {
  for (int d = std::max(1, std::min(n, limit)); d > 1; --d)
    if (n % d == 0) return d;
  return 1;
}

}  // namespace

int fixed_pass_size(const PassPlan& plan) {
  int size = plan.pass_spp;
  if (size <= 0) size = plan.time_budget_s > 0 ? kDefaultEqualPass : std::max(1, plan.target_spp);
  if (plan.equal_passes && plan.target_spp > 0) size = largest_divisor_at_most(plan.target_spp, size);
  return std::max(1, size);
}

int replay_sampler_spp(const PassPlan& plan) {
  return plan.equal_passes ? fixed_pass_size(plan) : std::max(1, plan.target_spp);
}

int adaptive_pass_size(double seconds_per_spp, double seconds_left, int previous, int spp_left) {
  if (seconds_left <= 0 || spp_left <= 0) return 0;
  if (!(seconds_per_spp > 0)) return std::min(spp_left, std::max(1, previous * 2));
  const double fits = kSafety * seconds_left / seconds_per_spp;  // samples per pixel that still fit
  if (fits < 1.0) return 0;
  const double aim =
      std::clamp(kPassShareOfTimeLeft * seconds_left, kMinPassSeconds, kMaxPassSeconds) / seconds_per_spp;
  const double n = std::min({fits, std::max(1.0, aim), static_cast<double>(spp_left)});
  return static_cast<int>(std::clamp(std::floor(n), 1.0, static_cast<double>(1 << 30)));
}

RenderOutcome render_passes(const RenderScene& scene, Film& film, WorkerPool& pool, const PassPlan& plan,
                            IntegratorSettings settings, const DriverCallbacks& callbacks) {
  RenderOutcome out;
  out.spp_done = plan.start_spp;
  const auto start = Clock::now();
  const bool adaptive = plan.time_budget_s > 0 && plan.pass_spp <= 0 && !plan.equal_passes;
  const int fixed = fixed_pass_size(plan);
  const int target = plan.target_spp > 0 ? plan.target_spp : (1 << 30);
  double seconds_per_spp = 0;
  int previous = 0;
  RenderCache cache;  // the passes' integrators learn once (RenderCache)
  if (settings.cache == nullptr) settings.cache = &cache;
  while (out.spp_done < target) {
    const double elapsed = seconds_since(start);
    const double left = plan.time_budget_s > 0 ? plan.time_budget_s - elapsed : 1e300;
    int n = adaptive ? adaptive_pass_size(seconds_per_spp, left, previous, target - out.spp_done)
                     : std::min(fixed, target - out.spp_done);
    // Under a budget a fixed-size pass runs only if it is expected to fit.
    if (!adaptive && plan.time_budget_s > 0 && seconds_per_spp > 0 && seconds_per_spp * n > kSafety * left) n = 0;
    if (n <= 0) break;
    if (plan.equal_passes && n < fixed) break;  // a smaller last pass would break the stratification
    settings.first_sample = out.spp_done;
    settings.spp = n;
    const std::unique_ptr<Integrator> integrator = callbacks.make_integrator(settings);
    const auto t0 = Clock::now();
    integrator->render(scene, film, pool);
    const double pass_s = seconds_since(t0);
    out.last_pass_seconds = pass_s;
    if (settings.monitor != nullptr && settings.monitor->cancelled()) {
      out.cancelled = true;
      break;
    }
    seconds_per_spp = pass_s / n;
    previous = n;
    out.spp_done += n;
    ++out.passes;
    if (callbacks.pass_done) callbacks.pass_done(out.spp_done);
  }
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace pt

// The render loop of the command line (docs/cli.md): progressive passes over
// sample ranges [first, first + n) until the sample target or the time budget
// is reached, or a signal cancels the render. Passes complete unless cancelled,
// so every pixel holds at least `spp_done` samples.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "render/integrators/integrator.h"

namespace pt {

class Film;
class RenderScene;
class WorkerPool;

struct PassPlan {
  int target_spp = 0;          // stop after this many samples per pixel; 0: none (then a budget is needed)
  double time_budget_s = 0.0;  // stop before the render time would exceed it; 0: none
  // Samples per pass: > 0 fixes it; 0 picks it (one pass for a sample target
  // alone; adapted from the measured pass time under a time budget).
  int pass_spp = 0;
  // True when the sampler stratifies over the pass's sample count (jittered,
  // and the pixel-grid samplers of the non-path integrators): then every pass
  // has the same size, a divisor of the target, and starts at a multiple of it.
  bool equal_passes = false;
  int start_spp = 0;           // samples already in the film (a resumed render)
};

// Fixed pass sizes (the size the plan gives every pass when not adaptive).
int fixed_pass_size(const PassPlan& plan);
// The sample count the samplers of the pass that rendered a sample of `plan`
// were made with, so that a replay (--pixel, --replay) draws it exactly as the
// render did: with equal passes (the jittered sampler and the classic pixel
// grid stratify per pass) every pass has fixed_pass_size(plan) samples; the
// other samplers (random, Sobol') do not depend on it (the target, or 1, then).
int replay_sampler_spp(const PassPlan& plan);
// Adaptive pass under a time budget: the next pass's size from the measured
// seconds per sample-per-pixel and the time left. 0 means stop.
int adaptive_pass_size(double seconds_per_spp, double seconds_left, int previous, int spp_left);

struct RenderOutcome {
  int spp_done = 0;         // complete samples per pixel (every pixel has at least these)
  int passes = 0;
  bool cancelled = false;   // stopped by a signal in the middle of a pass
  double seconds = 0.0;     // render time of this run (not of the resumed ones)
  double last_pass_seconds = 0.0;  // the last pass's, complete or cancelled: how far a budget can be overrun
};

struct DriverCallbacks {
  // Makes the integrator for one pass (`settings` has first_sample/spp set).
  std::function<std::unique_ptr<Integrator>(const IntegratorSettings& settings)> make_integrator;
  // After every complete pass, with the samples per pixel now in the film.
  std::function<void(int spp_done)> pass_done;
};

RenderOutcome render_passes(const RenderScene& scene, Film& film, WorkerPool& pool, const PassPlan& plan,
                            IntegratorSettings settings, const DriverCallbacks& callbacks);

}  // namespace pt

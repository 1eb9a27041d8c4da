// Integrators turn a RenderScene into pixels on a Film. Chosen by name through
// a registry (name -> factory); an unknown name gets an error listing the valid ones.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/film/film.h"
#include "render/render_scene.h"
#include "render/samplers/sampler.h"

namespace pt {

class WorkerPool;

// Which strategies the path integrator combines for lights that can be hit
// (area lights, the environment). Mis is the product; the other two exist so
// tests can check that all three converge to the same image.
enum class LightStrategy {
  Mis,        // next-event estimation and BSDF sampling, power heuristic
  LightOnly,  // next-event estimation only (emitters found by BSDF rays count only after delta bounces)
  BsdfOnly,   // BSDF sampling only (next-event estimation for delta lights only)
};

// Watches a render from outside: the command line's progress display, its
// signal handling and time budget. Called from worker threads, so
// implementations must be thread-safe.
class RenderMonitor {
 public:
  virtual ~RenderMonitor() = default;
  // Polled before each tile, each pixel and every 16 samples of a pixel (the
  // render loop's kCancelPollSamples): true stops the pass there, so a render
  // stops within a fraction of a second whatever its pass size. The film then
  // holds fewer samples in some pixels (a pixel stopped inside the pass keeps
  // the samples it got); each pixel's value is still the mean of its own
  // samples (PixelSum counts them).
  virtual bool cancelled() const { return false; }
  // After each finished (or cancelled) tile, with the number of pixel samples it rendered and
  // the rays it traced (RenderScene::intersect and occluded calls).
  virtual void tile_done(int64_t pixel_samples, int64_t rays) {
    (void)pixel_samples;
    (void)rays;
  }
};

// What an integrator learns before its samples (the path integrator's
// guides), kept across the passes of one render: render_passes() makes one
// per render, the integrator of its first pass stores its state in `slot`
// and those of the later passes reuse it (each pass's integrator is made
// anew with that pass's sample range; what was learned depends on none of it).
struct RenderCache {
  std::shared_ptr<const void> slot;
};

struct IntegratorSettings {
  int max_depth = 5;    // recursion limit (path: the number of bounces)
  int spp = 1;          // samples per pixel
  uint64_t seed = 0;
  int tile_size = 16;   // pixels per tile side; the image does not depend on it
  // Samples [first_sample, first_sample + spp) of every pixel are added to the
  // film: successive calls render progressive passes (the bench tools use it).
  int first_sample = 0;
  PixelFilterType filter = PixelFilterType::Box;  // the path integrator's pixel filter
  float clamp = 0.0f;   // path: largest channel of one sample's radiance; 0 = no clamp
  LightStrategy light_strategy = LightStrategy::Mis;
  // path: where the scene's lights are a few infinite ones (LightSet::each_lights:
  // a sun and a sky), next-event estimation samples each of them at every
  // vertex; false: it chooses one, as for every other scene (tests compare the two).
  bool estimate_each_light = true;
  // path: Russian roulette. From bounce `roulette_depth` on, a path whose
  // throughput (largest channel, times eta^2) t is below `roulette_threshold`
  // survives with probability t / roulette_threshold and is reweighted, so the
  // estimate stays unbiased. The defaults were chosen by measured efficiency
  // (1 / (MSE x time), tools/study/roulette/roulette_study.py, docs/path-tracing.md).
  int roulette_depth = 3;
  float roulette_threshold = 1.0f / 3.0f;
  SamplerType sampler = SamplerType::Sobol;  // path: where its random numbers come from (docs/samplers.md)
  // path: light guiding's pre-pass paths per pixel (render.light_guiding,
  // render/guiding/light_guide.h); 0 = off.
  int light_guiding = 0;
  // path: path guiding's pre-pass paths per pixel (render.path_guiding,
  // render/guiding/path_guide.h); 0 = off.
  int path_guiding = 0;
  // Cycles' Film > Transparent: what camera rays see when they hit nothing
  // (background, environment, background image) is left out of the image
  // (black, alpha 0); it still lights the scene and shows in reflections.
  bool film_transparent = false;
  // Replay: >= 0 renders only this sample index of every pixel of the film's
  // crop (the sampler still sees spp, so the sample is the one a full render draws).
  int only_sample = -1;
  RenderMonitor* monitor = nullptr;  // optional; not owned; the image does not depend on it unless it cancels
  RenderCache* cache = nullptr;      // optional; not owned; null: every render() call learns anew
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Renders every pixel of `film`. Parallel over tiles inside `pool`; the
  // result does not depend on the thread count or the tile order.
  virtual void render(const RenderScene& scene, Film& film, WorkerPool& pool) const = 0;
  // Whether this integrator can render `scene` at all (e.g. a debug view that
  // needs a backend able to count its work); if not, `why` says so. Asked
  // before rendering; the default accepts every scene.
  virtual bool can_render(const RenderScene& scene, std::string& why) const {
    (void)scene;
    (void)why;
    return true;
  }
};

using IntegratorFactory = std::unique_ptr<Integrator> (*)(const IntegratorSettings& settings);

// How an integrator reads the scene's lights.
enum class LightModel {
  None,      // a debug view: lights play no part
  Classic,   // whitted: the ambient term, spot lights' linear falloff (docs/rendering.md)
  Physical,  // path: no ambient term (a warning), spot lights' smoothstep (docs/path-tracing.md)
};

// A registry entry: the integrator's name, its factory, and the facts the
// command line needs before making one.
struct IntegratorInfo {
  const char* name;
  IntegratorFactory make;
  // true: samples come from settings.sampler and are weighted by
  // settings.filter (path); false: the classic pixel grid, stratified over each
  // pass's sample count, and the box filter.
  bool configurable_sampling;
  // The AOVs it produces (the render loop's, and its own lighting split);
  // any other is refused before rendering (check_aovs).
  AovSet aovs;
  LightModel lights;

  bool produces(AovType type) const { return (aovs & aov_bit(type)) != 0; }
  // False, with `error` naming the first AOV of `requested` it cannot produce
  // and listing those it can.
  bool check_aovs(const std::vector<AovRequest>& requested, std::string& error) const;

  // What takes the samples with `sampler` and `filter` (the EXR stamp, the run
  // record): the configured ones, or "pixel-grid" and "box".
  const char* sampler_name(SamplerType sampler) const;
  const char* filter_name(PixelFilterType filter) const;
  // How it chooses among the lights (the EXR stamp, the run record): the
  // scene's render.light_sampler for the path integrator, which samples one
  // light per vertex; "all" for whitted, which visits every light; "none" for
  // the views, which ignore lights.
  const char* light_sampler_name(LightSamplerType light_sampler) const;
  // Whether every pass must have the same size (a divisor of the target): the
  // sampler stratifies over the pass's sample count (jittered, the pixel grid).
  bool equal_passes(SamplerType sampler) const;
};

// The entry named `name`; nullptr with `error` (listing the valid names) if none.
const IntegratorInfo* find_integrator(const std::string& name, std::string& error);
// Returns nullptr and sets `error` (listing the valid names) for an unknown name.
std::unique_ptr<Integrator> make_integrator(const std::string& name, const IntegratorSettings& settings,
                                            std::string& error);
std::vector<std::string> integrator_names();

}  // namespace pt

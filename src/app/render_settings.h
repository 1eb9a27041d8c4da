// The settings of one render, resolved once from the scene (its --set
// overrides already applied by the loader) and the command line: the
// integrator and what the registry says of it, the integrator's settings, and
// the image size. Everything else that names a setting derives from this one
// value: the integrator of every pass, the build options, the EXR stamp, the
// run record, the checkpoint identity and the summary line.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "accel/accelerator.h"
#include "core/diagnostics.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"

namespace pt {

struct RenderStamp;
struct RunRecord;
struct SceneDescription;

// What a command line changes; each default keeps the scene's value (or, for
// the settings a scene does not have, IntegratorSettings' default).
struct SettingsOverrides {
  std::string integrator;    // empty: the scene's
  int max_depth = -1;        // < 0: the scene's
  uint64_t seed = 0;
  std::string filter;        // one of kPixelFilterNames; empty: the scene's
  SamplerType sampler = IntegratorSettings{}.sampler;
  float clamp = -1.0f;       // < 0: the scene's
  int roulette_depth = IntegratorSettings{}.roulette_depth;
  float roulette_threshold = IntegratorSettings{}.roulette_threshold;
  int width = 0, height = 0; // > 0: replaces the scene's (one alone keeps the aspect ratio)
  bool film_transparent = false;  // true: transparent whatever the scene says
};

struct RenderSettings {
  const IntegratorInfo* integrator = nullptr;  // the registry's entry
  // max depth, seed, filter, clamp, sampler, Russian roulette; each pass sets
  // its own spp and first_sample on a copy.
  IntegratorSettings integration;
  int width = 0, height = 0;  // the image, after the overrides
  LightSamplerType light_sampler = LightSamplerType::Bvh;  // the scene's render.light_sampler
  float shadow_terminator_offset = kDefaultShadowTerminatorOffset;  // render.shadow_terminator_geometry_offset

  std::string integrator_name() const { return integrator->name; }
  // The integrator of one pass (or replay, or the can_render question).
  std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings) const {
    return integrator->make(settings);
  }
  // What takes the samples (the registry's names: path's sampler and filter,
  // the classic integrators' "pixel-grid" and "box").
  const char* sampler_name() const { return integrator->sampler_name(integration.sampler); }
  const char* filter_name() const { return integrator->filter_name(integration.filter); }
  const char* light_sampler_name() const { return integrator->light_sampler_name(light_sampler); }
  // render.light_guiding where it is used (the integrators that choose one
  // light per vertex); 0 for the others.
  int light_guiding() const { return integrator->lights == LightModel::Physical ? integration.light_guiding : 0; }
  // render.path_guiding where it is used (the path integrator); 0 for the others.
  int path_guiding() const { return integrator->lights == LightModel::Physical ? integration.path_guiding : 0; }
  bool equal_passes() const { return integrator->equal_passes(integration.sampler); }

  BuildOptions build_options(AccelKind accel) const;
  // The stamp's settings (integrator, sampler, filter, light sampler, light
  // guiding, shadow terminator offset, seed, max depth, clamp, version); the
  // caller adds what the render reached.
  RenderStamp stamp() const;
  // The run record's settings (the same, and the image size).
  void describe(RunRecord& record) const;
  // The settings a checkpoint must match to be resumed (not the pass size):
  // integrator, width, height, max_depth, seed, sampler, filter, clamp, and
  // film_transparent, light_sampler and shadow_terminator_geometry_offset
  // when not the default.
  nlohmann::ordered_json identity() const;
};

// Resolves the settings of `desc` under `overrides`; false after reporting an
// unknown integrator to `diag` (at the scene's "integrator" when it came from there).
bool resolve_render_settings(const SceneDescription& desc, const SettingsOverrides& overrides, RenderSettings& out,
                             Diagnostics& diag);

}  // namespace pt

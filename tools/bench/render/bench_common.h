// Shared pieces of the rendering benchmarks: loading a scene into a render
// scene on a chosen backend, progressive rendering into one film, and the
// error metrics against a reference image.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "app/render_settings.h"
#include "core/image.h"
#include "core/parallel.h"
#include "core/stopwatch.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/scene_description.h"

namespace pt::bench {

struct LoadedScene {
  SceneDescription desc;
  // The scene's settings (integrator, max depth, filter, clamp) with the
  // tool's sampler and Russian roulette (--sampler, --rr-depth, --rr-threshold):
  // resolved as the pathtracer resolves its own (app/render_settings.h).
  RenderSettings settings;
  std::unique_ptr<RenderScene> scene;
  double load_seconds = 0, build_seconds = 0;
};

// Loads `path`, resolves its settings under `overrides` and builds it on
// backend `accel` inside `pool`; nullopt after printing the diagnostics to stderr.
std::optional<LoadedScene> load(const std::string& path, AccelKind accel, const SettingsOverrides& overrides,
                                WorkerPool& pool);

// The scene's integrator settings with `spp` samples starting at `first_sample`.
IntegratorSettings settings_for(const LoadedScene& s, int spp, int first_sample, uint64_t seed);

// Error metrics over all pixels and the three channels, linear values.
struct ImageError {
  double rmse = 0;     // sqrt(mean (x - r)^2)
  double relmse = 0;   // mean (x - r)^2 / (r^2 + 0.01)
  double mean_ratio[3] = {0, 0, 0};  // per channel: mean(x) / mean(r)
};
ImageError compare(const Image& image, const Image& reference);

// Where the squared error comes from: the pixels are put in regions by the
// reference alone (docs/path-tracing.md, "Where the error is"):
//  - "light interior": the emitter itself (a reference channel above
//    kLightLevel, here and in the 8 neighbours);
//  - "light edge": the rest of the pixels within 2 pixels of a light pixel
//    (those the light's edge crosses, and their neighbours);
//  - "edge": elsewhere, a 4-neighbour differs by more than 25% of the
//    brighter one's luminance (object silhouettes, wall corners, shadow edges);
//  - "smooth": the rest.
// For each: its share of the pixels, its share of the image's squared error,
// and its own RMSE.
struct RegionError {
  const char* name = "";
  double pixel_share = 0, error_share = 0, rmse = 0;
};
inline constexpr double kLightLevel = 2.0;
std::vector<RegionError> error_breakdown(const Image& image, const Image& reference);
// The per-pixel squared error, mean over the channels, in every channel (an
// image to look at, e.g. with a logarithmic colour scale).
Image error_map(const Image& image, const Image& reference);

}  // namespace pt::bench

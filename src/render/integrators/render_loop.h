// The pixel loop shared by every integrator: tiles rendered in parallel inside
// the worker pool, each pixel computed entirely by one task from a sampler
// whose numbers depend on (seed, pixel, sample index, dimension) only, so the
// image is bit-identical for any thread count, tile size and tile order.
#pragma once

#include <cstdint>
#include <memory>

#include "core/color.h"
#include "core/function_ref.h"
#include "core/math.h"
#include "render/camera/ray_differential.h"
#include "render/film/aov.h"
#include "render/film/filter.h"
#include "render/integrators/integrator.h"
#include "render/samplers/sampler.h"

namespace pt {

class Film;
class WorkerPool;
struct RenderScene;

// Film position (in pixels) of sample `index` of `spp` in pixel (x, y) under
// the classic integrators' StratifiedPixelSampler:
//  - spp == 1: the pixel centre;
//  - spp a perfect square n*n: one jittered sample in each cell of an n x n grid
//    (sample `index` in cell index mod spp: each pass of spp samples fills it once);
//  - otherwise: uniformly random positions in the pixel.
// The jitter comes from Rng(hash(seed, pixel_index, index)).
Vec2f sample_position(int x, int y, int index, int spp, uint64_t seed, uint64_t pixel_index);

// What an integrator returns for one camera ray: its radiance estimate and
// whether the ray hit a surface (the pixel's coverage: the beauty's alpha;
// with IntegratorSettings::film_transparent a miss adds no radiance).
struct CameraEstimate {
  RGB radiance;
  bool hit = false;
};

// Computes one radiance estimate for a camera ray (with its differential in a
// scene whose textures filter: pass ray.differential_or_null() to the first
// RenderScene::intersect; a callable taking a plain Ray works too).
using RadianceFn = FunctionRef<CameraEstimate(const CameraRay&)>;
// Computes one radiance estimate for a camera ray, drawing further dimensions
// from `sampler`. `aov` is null unless the film asks for the lighting split
// (Film::wants_lighting()); then the estimate's parts go there.
using SampleRadianceFn = FunctionRef<CameraEstimate(const CameraRay&, Sampler&, AovSample* aov)>;

// The general loop: for samples [settings.first_sample, + settings.spp) of every
// pixel, starts `sampler` (a prototype copied into each task) at the sample,
// draws the film position through `filter`, the lens position if the camera has
// a lens, and adds weight * radiance to the film. Only the film's crop window is
// rendered (in frame coordinates, so its pixels equal a full render's). With
// settings.only_sample >= 0 only that sample index is rendered (replay).
// Non-finite estimates count as black and are reported in film.non_finite().
// With settings.film_transparent, a camera ray that hits nothing adds black
// (and no lighting AOV): the background is seen as transparent, not lit.
// Geometric AOVs (Film::wants_geometry) come from intersecting the camera ray
// once more. Runs tiles (scheduled_tile_size) in parallel inside `pool`.
void render_samples(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                    const Sampler& sampler, const PixelFilter& filter, SampleRadianceFn radiance);

// The side of the tiles render_samples schedules for a crop of width x height
// on `threads` threads: `requested` (IntegratorSettings::tile_size), halved
// down to kMinTileSize pixels while there are fewer than kTilesPerThread tiles
// per thread, so that on many threads the last tiles are a small share of a
// small image. The image does not depend on it.
inline constexpr int kTilesPerThread = 32;
inline constexpr int kMinTileSize = 4;
int scheduled_tile_size(int requested, int width, int height, int threads);

// Fills the geometric part of `aov` (albedo, normal, position, depth, ids,
// Cryptomatte ids) for a camera ray.
void first_hit_aovs(const RenderScene& scene, const CameraRay& ray, AovSample& aov);

// The classic integrators' loop: render_samples with the StratifiedPixelSampler
// and the box filter, so each pixel is the average (in double) of `radiance`
// over settings.spp camera rays.
void render_pixels(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                   RadianceFn radiance);

// The same for an integrator that splits its estimate into the lighting AOVs
// (whitted): `aov` is null unless the film asks for them (Film::wants_lighting()).
// Further sample dimensions (area lights' samples) come from the sampler, whose
// numbers depend on (seed, pixel, sample index) only (StratifiedPixelSampler).
void render_pixels_with_split(const RenderScene& scene, Film& film, WorkerPool& pool,
                              const IntegratorSettings& settings, SampleRadianceFn radiance);

}  // namespace pt

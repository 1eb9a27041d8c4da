#include "render/integrators/render_loop.h"

#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/render_scene.h"

namespace pt {
namespace {

// Samples of one pixel between two polls of the render's cancel flag (one
// relaxed atomic load behind a virtual call): a few nanoseconds against the
// microseconds of 16 samples.
constexpr int kCancelPollSamples = 16;

// The samples [first, end) each pixel takes in this pass.
std::pair<int, int> sample_range(const IntegratorSettings& settings) {
  if (settings.only_sample >= 0) return {settings.only_sample, settings.only_sample + 1};
  const int first = std::max(0, settings.first_sample);
  return {first, first + std::max(0, settings.spp)};
}

// The camera ray through `film_px`, with its differential when the scene's
// textures filter over footprints (RenderScene::footprints).
CameraRay camera_ray(const RenderScene& scene, Sampler& sampler, Vec2f film_px, bool lens, bool differentials) {
  const Vec2f lens_sample = lens ? sampler.get_2d() : Vec2f(0.5f, 0.5f);
  CameraRay ray(lens ? scene.camera.generate_ray(film_px, lens_sample) : scene.camera.generate_ray(film_px));
  if (differentials) {
    ray.differential = scene.camera.differential(film_px, lens_sample);
    ray.has_differential = true;
  }
  return ray;
}

}  // namespace

int scheduled_tile_size(int requested, int width, int height, int threads) {
  int tile = std::max(1, requested);
  const auto tiles = [&](int t) {
    return static_cast<int64_t>((width + t - 1) / t) * static_cast<int64_t>((height + t - 1) / t);
  };
  while (tile / 2 >= kMinTileSize && tiles(tile) < static_cast<int64_t>(kTilesPerThread) * std::max(1, threads))
    tile /= 2;
  return tile;
}

Vec2f sample_position(int x, int y, int index, int spp, uint64_t seed, uint64_t pixel_index) {
  StratifiedPixelSampler sampler(spp, seed, 1);
  sampler.start(pixel_index, index);
  return Vec2f(static_cast<float>(x), static_cast<float>(y)) + sampler.get_pixel_2d();
}

void first_hit_aovs(const RenderScene& scene, const CameraRay& ray, AovSample& aov) {
  Intersection isect;
  if (!scene.intersect(ray, isect, ray.differential_or_null())) return;
  aov.hit = true;
  aov.albedo = isect.material->albedo_at(tex_coord(isect.geo));
  const Vec3f wo = -ray.dir;
  const bool front = dot(isect.geo.ng, wo) >= 0.0f;
  aov.normal = front ? isect.geo.ns : -isect.geo.ns;
  aov.position = isect.geo.p;
  aov.depth = scene.camera.depth(isect.geo.p);
  aov.object = isect.hit.shape + 1;
  // The material the hit was shaded with (an instance's replaces its shapes').
  const int material = scene.material_of(isect.hit.shape, isect.hit.instance);
  aov.material = static_cast<uint32_t>(material) + 1;
  aov.crypto_object = scene.names.object_id(isect.hit.shape, isect.hit.instance);
  aov.crypto_material = scene.names.material_ids[static_cast<std::size_t>(material)];
}

// One task per tile (simple_partitioner, grain 1), in row-major order: a
// thread that runs out of work steals whole tiles, so the render's tail, the
// time the last tile runs while the other threads have nothing left, is at
// most one tile's time (auto_partitioner's ranges can leave several tiles to
// one thread at the end; docs/bench/threads.md, session 13).
void render_samples(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                    const Sampler& prototype, const PixelFilter& filter, SampleRadianceFn radiance) {
  const PixelRect crop = film.crop();
  const int tile = scheduled_tile_size(settings.tile_size, crop.width(), crop.height(), pool.threads());
  const int first = sample_range(settings).first, end = sample_range(settings).second;  // clang 14 can't capture [a, b]
  const int tiles_x = (crop.width() + tile - 1) / tile;
  const int tiles_y = (crop.height() + tile - 1) / tile;
  const bool lens = scene.camera.has_lens();
  RenderMonitor* const monitor = settings.monitor;
  const bool geometry = film.wants_geometry(), lighting = film.wants_lighting();
  const bool transparent = settings.film_transparent;
  const bool aovs = film.aov_slots() > 0;
  std::mutex report_mutex;
  NonFiniteReport report;

  // Returns the number of samples it added: fewer than the pass's when the
  // monitor cancels the render inside the pixel (polled every
  // kCancelPollSamples samples, so that a signal is seen within a fraction of
  // a second even in a single pass of many samples per pixel). The pixel then
  // keeps the samples it got: its value is their mean, and PixelSum counts them.
  auto render_pixel = [&](Sampler& sampler, AovScratch& scratch, NonFiniteReport& bad, int x, int y) {
    const Vec2f corner(static_cast<float>(x), static_cast<float>(y));
    PixelSum sum;
    scratch.clear();
    AovSample aov;  // reset per sample only when the film has AOVs
    int s = first;
    for (; s < end; ++s) {
      if (monitor != nullptr && s > first && (s - first) % kCancelPollSamples == 0 && monitor->cancelled()) break;
      sampler.start_pixel_sample(x, y, s);
      const FilterSample fs = filter.sample(sampler.get_pixel_2d());
      const Vec2f film_px = corner + fs.offset;
      const CameraRay ray = camera_ray(scene, sampler, film_px, lens, scene.footprints);
      if (aovs) aov = AovSample{};
      CameraEstimate e = radiance(ray, sampler, lighting ? &aov : nullptr);
      if (transparent && !e.hit) {  // the background is not part of the image: only lights the scene
        e.radiance = RGB();
        if (lighting) aov = AovSample{};
      }
      const RGB c = e.radiance;
      const bool finite = c.is_finite();
      if (!finite) bad.record(x, y, s, c);
      sum.add(finite ? c : RGB(), fs.weight, e.hit);
      if (aovs) {
        if (geometry) first_hit_aovs(scene, ray, aov);
        film.accumulate(scratch, aov, c, fs.weight, !finite);
      }
    }
    film.add(x, y, sum);
    if (aovs) film.add_aovs(x, y, scratch);
    return static_cast<int64_t>(s - first);
  };

  pool.run([&] {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, tiles_x * tiles_y, 1),
        [&](const tbb::blocked_range<int>& r) {
          Sampler sampler = prototype;
          AovScratch scratch = film.make_scratch();
          NonFiniteReport bad;
          for (int t = r.begin(); t != r.end(); ++t) {
            if (monitor != nullptr && monitor->cancelled()) break;
            const int x0 = crop.x0 + (t % tiles_x) * tile, y0 = crop.y0 + (t / tiles_x) * tile;
            const int x1 = std::min(crop.x1, x0 + tile), y1 = std::min(crop.y1, y0 + tile);
            const uint64_t rays_before = rays_traced_by_this_thread();
            int64_t samples = 0;
            for (int y = y0; y < y1; ++y)
              for (int x = x0; x < x1; ++x) {
                if (monitor != nullptr && monitor->cancelled()) break;  // each pixel: a pass may be long
                samples += render_pixel(sampler, scratch, bad, x, y);
              }
            if (monitor != nullptr)
              monitor->tile_done(samples, static_cast<int64_t>(rays_traced_by_this_thread() - rays_before));
          }
          if (bad.total() > 0) {
            const std::lock_guard<std::mutex> lock(report_mutex);
            report.merge(bad);
          }
        }, tbb::simple_partitioner());
  });
  film.add_non_finite(report);
}

void render_pixels_with_split(const RenderScene& scene, Film& film, WorkerPool& pool,
                              const IntegratorSettings& settings, SampleRadianceFn radiance) {
  const StratifiedPixelSampler sampler(settings.spp, settings.seed, film.width());
  const PixelFilter box(PixelFilterType::Box);
  render_samples(scene, film, pool, settings, sampler, box, radiance);
}

void render_pixels(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                   RadianceFn radiance) {
  render_pixels_with_split(scene, film, pool, settings,
                           [&](const CameraRay& ray, Sampler&, AovSample*) { return radiance(ray); });
}

}  // namespace pt

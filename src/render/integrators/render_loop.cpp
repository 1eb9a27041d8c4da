#include "render/integrators/render_loop.h"

#include <algorithm>
#include <mutex>
#include <vector>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/render_scene.h"

namespace pt {

Vec2f sample_position(int x, int y, int index, int spp, uint64_t seed, uint64_t pixel_index) {
  StratifiedPixelSampler sampler(spp, seed, 1);
  sampler.start(pixel_index, index);
  return Vec2f(static_cast<float>(x), static_cast<float>(y)) + sampler.get_pixel_2d();
}

void first_hit_aovs(const RenderScene& scene, const Ray& ray, AovSample& aov) {
  Intersection isect;
  if (!scene.intersect(ray, isect)) return;
  aov.hit = true;
  aov.albedo = isect.material->albedo_at(isect.geo.uv);
  const Vec3f wo = -ray.dir;
  const bool front = dot(isect.geo.ng, wo) >= 0.0f;
  aov.normal = front ? isect.geo.ns : -isect.geo.ns;
  aov.position = isect.geo.p;
  aov.depth = scene.camera.depth(isect.geo.p);
  aov.object = isect.hit.shape + 1;
  aov.material = isect.hit.shape < scene.shape_material.size()
                     ? static_cast<uint32_t>(scene.shape_material[isect.hit.shape]) + 1
                     : 0;
}

void render_samples(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                    const Sampler& prototype, const PixelFilter& filter, SampleRadianceFn radiance) {
  const PixelRect crop = film.crop();
  const int tile = std::max(1, settings.tile_size);
  int first = std::max(0, settings.first_sample);
  int end = first + std::max(0, settings.spp);
  if (settings.only_sample >= 0) {
    first = settings.only_sample;
    end = first + 1;
  }
  const int tiles_x = (crop.width() + tile - 1) / tile;
  const int tiles_y = (crop.height() + tile - 1) / tile;
  const bool lens = scene.camera.has_lens();
  RenderMonitor* const monitor = settings.monitor;
  const bool geometry = film.wants_geometry(), lighting = film.wants_lighting();
  const bool aovs = film.aov_slots() > 0;
  std::mutex report_mutex;
  NonFiniteReport report;

  auto render_pixel = [&](Sampler& sampler, AovScratch& scratch, NonFiniteReport& bad, int x, int y) {
    const Vec2f corner(static_cast<float>(x), static_cast<float>(y));
    PixelSum sum;
    scratch.clear();
    AovSample aov;  // reset per sample only when the film has AOVs
    for (int s = first; s < end; ++s) {
      sampler.start_pixel_sample(x, y, s);
      const FilterSample fs = filter.sample(sampler.get_pixel_2d());
      const Vec2f film_px = corner + fs.offset;
      const Ray ray = lens ? scene.camera.generate_ray(film_px, sampler.get_2d()) : scene.camera.generate_ray(film_px);
      if (aovs) aov = AovSample{};
      const RGB c = radiance(ray, sampler, lighting ? &aov : nullptr);
      const bool finite = c.is_finite();
      if (!finite) bad.record(x, y, s, c);
      sum.add(finite ? c : RGB(), fs.weight);
      if (aovs) {
        if (geometry) first_hit_aovs(scene, ray, aov);
        film.accumulate(scratch, aov, c, fs.weight, !finite);
      }
    }
    film.add(x, y, sum);
    if (aovs) film.add_aovs(x, y, scratch);
  };

  pool.run([&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, tiles_y, 0, tiles_x), [&](const tbb::blocked_range2d<int>& r) {
      Sampler sampler = prototype;
      AovScratch scratch = film.make_scratch();
      NonFiniteReport bad;
      for (int ty = r.rows().begin(); ty != r.rows().end(); ++ty) {
        for (int tx = r.cols().begin(); tx != r.cols().end(); ++tx) {
          if (monitor != nullptr && monitor->cancelled()) break;
          const int x0 = crop.x0 + tx * tile, y0 = crop.y0 + ty * tile;
          const int x1 = std::min(crop.x1, x0 + tile), y1 = std::min(crop.y1, y0 + tile);
          const uint64_t rays_before = rays_traced_by_this_thread();
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) render_pixel(sampler, scratch, bad, x, y);
          if (monitor != nullptr)
            monitor->tile_done(static_cast<int64_t>(x1 - x0) * (y1 - y0) * (end - first),
                               static_cast<int64_t>(rays_traced_by_this_thread() - rays_before));
        }
      }
      if (bad.total() > 0) {
        const std::lock_guard<std::mutex> lock(report_mutex);
        report.merge(bad);
      }
    });
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
                           [&](const Ray& ray, Sampler&, AovSample*) { return radiance(ray); });
}

}  // namespace pt

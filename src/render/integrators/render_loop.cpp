#include "render/integrators/render_loop.h"

#include <algorithm>

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

Vec2f lens_position(int index, uint64_t seed, uint64_t pixel_index) {
  StratifiedPixelSampler sampler(1, seed, 1);
  sampler.start(pixel_index, index);
  return sampler.get_2d();
}

void render_samples(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                    const Sampler& prototype, const PixelFilter& filter, SampleRadianceFn radiance) {
  const int width = film.width(), height = film.height();
  const int tile = std::max(1, settings.tile_size);
  const int first = std::max(0, settings.first_sample);
  const int end = first + std::max(0, settings.spp);
  const int tiles_x = (width + tile - 1) / tile;
  const int tiles_y = (height + tile - 1) / tile;
  const bool lens = scene.camera.has_lens();
  RenderMonitor* const monitor = settings.monitor;

  auto render_pixel = [&](Sampler& sampler, int x, int y) {
    const Vec2f corner(static_cast<float>(x), static_cast<float>(y));
    PixelSum sum;
    for (int s = first; s < end; ++s) {
      sampler.start_pixel_sample(x, y, s);
      const FilterSample fs = filter.sample(sampler.get_pixel_2d());
      const Vec2f film_px = corner + fs.offset;
      const Ray ray = lens ? scene.camera.generate_ray(film_px, sampler.get_2d()) : scene.camera.generate_ray(film_px);
      const RGB c = radiance(ray, sampler);
      sum.add(c.is_finite() ? c : RGB(), fs.weight);
    }
    film.add(x, y, sum);
  };

  pool.run([&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, tiles_y, 0, tiles_x), [&](const tbb::blocked_range2d<int>& r) {
      Sampler sampler = prototype;
      for (int ty = r.rows().begin(); ty != r.rows().end(); ++ty) {
        for (int tx = r.cols().begin(); tx != r.cols().end(); ++tx) {
          if (monitor != nullptr && monitor->cancelled()) return;
          const int x1 = std::min(width, (tx + 1) * tile), y1 = std::min(height, (ty + 1) * tile);
          for (int y = ty * tile; y < y1; ++y)
            for (int x = tx * tile; x < x1; ++x) render_pixel(sampler, x, y);
          if (monitor != nullptr)
            monitor->tile_done(static_cast<int64_t>(x1 - tx * tile) * (y1 - ty * tile) * (end - first));
        }
      }
    });
  });
}

void render_pixels(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                   RadianceFn radiance) {
  const StratifiedPixelSampler sampler(settings.spp, settings.seed, film.width());
  const PixelFilter box(PixelFilterType::Box);
  render_samples(scene, film, pool, settings, sampler, box,
                 [&](const Ray& ray, Sampler&) { return radiance(ray); });
}

}  // namespace pt

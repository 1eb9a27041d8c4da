#include "render/integrators/render_loop.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include "core/parallel.h"
#include "core/rng.h"
#include "render/film/film.h"
#include "render/render_scene.h"

namespace pt {

namespace {

// Largest n with n * n <= v.
int integer_sqrt(int v) {
  int n = static_cast<int>(std::sqrt(static_cast<double>(v)));
  while (n * n > v) --n;
  while ((n + 1) * (n + 1) <= v) ++n;
  return n;
}

}  // namespace

Vec2f sample_position(int x, int y, int index, int spp, uint64_t seed, uint64_t pixel_index) {
  const Vec2f corner(static_cast<float>(x), static_cast<float>(y));
  if (spp <= 1) return corner + Vec2f(0.5f, 0.5f);
  Rng rng(hash_keys(seed, pixel_index, static_cast<uint64_t>(index)));
  const float u = rng.next_float();
  const float v = rng.next_float();
  const int n = integer_sqrt(spp);
  if (n * n == spp) {
    const int cx = index % n, cy = index / n;
    const float inv = 1.0f / static_cast<float>(n);
    return corner + Vec2f((static_cast<float>(cx) + u) * inv, (static_cast<float>(cy) + v) * inv);
  }
  return corner + Vec2f(u, v);
}

Vec2f lens_position(int index, uint64_t seed, uint64_t pixel_index) {
  constexpr uint64_t kLensStream = 0x6c656e73;  // "lens": independent of the film jitter
  Rng rng(hash_keys(hash_keys(seed, kLensStream), pixel_index, static_cast<uint64_t>(index)));
  const float u = rng.next_float();
  return {u, rng.next_float()};
}

void render_pixels(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                   RadianceFn radiance) {
  const int width = film.width(), height = film.height();
  const int tile = std::max(1, settings.tile_size);
  const int spp = std::max(1, settings.spp);
  const int tiles_x = (width + tile - 1) / tile;
  const int tiles_y = (height + tile - 1) / tile;

  auto render_pixel = [&](int x, int y) {
    const uint64_t pixel_index = static_cast<uint64_t>(y) * static_cast<uint64_t>(width) + static_cast<uint64_t>(x);
    double sum[3] = {0, 0, 0};
    for (int s = 0; s < spp; ++s) {
      const Vec2f film_px = sample_position(x, y, s, spp, settings.seed, pixel_index);
      const Ray ray = scene.camera.has_lens()
                          ? scene.camera.generate_ray(film_px, lens_position(s, settings.seed, pixel_index))
                          : scene.camera.generate_ray(film_px);
      const RGB c = radiance(ray);
      if (!c.is_finite()) continue;
      sum[0] += c.r;
      sum[1] += c.g;
      sum[2] += c.b;
    }
    const double inv = 1.0 / spp;
    film.set_pixel(x, y, RGB(static_cast<float>(sum[0] * inv), static_cast<float>(sum[1] * inv),
                             static_cast<float>(sum[2] * inv)));
  };

  pool.run([&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, tiles_y, 0, tiles_x), [&](const tbb::blocked_range2d<int>& r) {
      for (int ty = r.rows().begin(); ty != r.rows().end(); ++ty) {
        for (int tx = r.cols().begin(); tx != r.cols().end(); ++tx) {
          const int x1 = std::min(width, (tx + 1) * tile), y1 = std::min(height, (ty + 1) * tile);
          for (int y = ty * tile; y < y1; ++y)
            for (int x = tx * tile; x < x1; ++x) render_pixel(x, y);
        }
      }
    });
  });
}

}  // namespace pt

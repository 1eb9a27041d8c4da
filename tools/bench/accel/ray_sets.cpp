#include "ray_sets.h"

#include <cmath>

#include <tbb/parallel_for.h>

#include "core/parallel.h"
#include "core/rng.h"

namespace pt::bench {

namespace {

// Cosine-weighted direction about unit n (Malley's method).
Vec3f cosine_direction(Vec3f n, float u1, float u2) {
  const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
  const float x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0f, 1.0f - u1));
  Vec3f t, b;
  orthonormal_basis(n, t, b);
  return normalize(x * t + y * b + z * n);
}

}  // namespace

RaySets make_ray_sets(const BenchScene& scene, const Accelerator& reference, WorkerPool& pool, uint64_t seed) {
  RaySets sets;
  sets.width = scene.width;
  sets.height = scene.height;
  const std::size_t n = static_cast<std::size_t>(scene.width) * static_cast<std::size_t>(scene.height);
  sets.camera.rays.resize(n);
  sets.camera.pixel.resize(n);
  // Per pixel: whether it has a shadow and a diffuse ray, and what they are.
  std::vector<Ray> shadow(n), diffuse(n);
  std::vector<char> has_hit(n, 0);
  pool.run([&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      const int x = static_cast<int>(i % static_cast<std::size_t>(scene.width));
      const int y = static_cast<int>(i / static_cast<std::size_t>(scene.width));
      const Ray ray = scene.camera.generate_ray(Vec2f(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f));
      sets.camera.rays[i] = ray;
      sets.camera.pixel[i] = static_cast<uint32_t>(i);
      Hit hit;
      if (!reference.intersect(ray, hit)) return;
      const SurfaceGeometry sg =
          surface(scene.geometry.shapes[hit.shape], hit.prim, ray, PrimHit{hit.t, hit.uv});
      if (!is_finite(sg.p) || !is_finite(sg.ng)) return;
      Rng rng(hash_keys(seed, i));
      const Vec3f light = scene.lights[i % scene.lights.size()];
      shadow[i] = spawn_ray_to(sg, light);
      const Vec3f facing = dot(sg.ng, ray.dir) < 0.0f ? sg.ng : -sg.ng;
      const float u1 = rng.next_float(), u2 = rng.next_float();
      diffuse[i] = spawn_ray(sg, cosine_direction(facing, u1, u2));
      has_hit[i] = 1;
    });
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (!has_hit[i]) continue;
    sets.shadow.rays.push_back(shadow[i]);
    sets.shadow.pixel.push_back(static_cast<uint32_t>(i));
    sets.diffuse.rays.push_back(diffuse[i]);
    sets.diffuse.pixel.push_back(static_cast<uint32_t>(i));
  }
  return sets;
}

}  // namespace pt::bench

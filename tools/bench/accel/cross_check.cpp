#include "cross_check.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/parallel.h"

namespace pt::bench {

namespace {

Verdict compare_nearest(const Accelerator& a, const Accelerator& b, const Ray& ray, float tolerance) {
  Hit ha, hb;
  const bool fa = a.intersect(ray, ha), fb = b.intersect(ray, hb);
  if (fa != fb) return Verdict::HitMiss;
  if (!fa) return Verdict::Agree;
  const float scale = std::max({ha.t, hb.t, length(ray.origin) / length(ray.dir), 1e-3f});
  if (!(std::fabs(ha.t - hb.t) <= tolerance * scale)) return Verdict::Distance;
  // The same primitive of another placement of the same object is a different surface.
  return (ha.shape == hb.shape && ha.prim == hb.prim && ha.instance == hb.instance) ? Verdict::Agree : Verdict::Tie;
}

Verdict compare_any(const Accelerator& a, const Accelerator& b, const Ray& ray) {
  return a.occluded(ray) == b.occluded(ray) ? Verdict::Agree : Verdict::HitMiss;
}

void tally(CrossCheckCounts& c, Verdict v) {
  ++c.rays;
  switch (v) {
    case Verdict::Agree: ++c.agree; break;
    case Verdict::Tie: ++c.tie; break;
    case Verdict::HitMiss: ++c.hit_miss; break;
    case Verdict::Distance: ++c.distance; break;
  }
}

int severity(Verdict v) {
  switch (v) {
    case Verdict::Agree: return 0;
    case Verdict::Tie: return 1;
    case Verdict::Distance: return 2;
    case Verdict::HitMiss: return 3;
  }
  return 0;
}

void check_set(const RaySet& set, bool any_hit, const Accelerator& a, const Accelerator& b, WorkerPool& pool,
               float tolerance, CrossCheckCounts& counts, std::vector<Verdict>& pixel) {
  std::vector<Verdict> verdict(set.rays.size(), Verdict::Agree);
  pool.run([&] {
    tbb::parallel_for(std::size_t{0}, set.rays.size(), [&](std::size_t i) {
      verdict[i] = any_hit ? compare_any(a, b, set.rays[i]) : compare_nearest(a, b, set.rays[i], tolerance);
    });
  });
  for (std::size_t i = 0; i < verdict.size(); ++i) {
    tally(counts, verdict[i]);
    Verdict& p = pixel[set.pixel[i]];
    if (severity(verdict[i]) > severity(p)) p = verdict[i];
  }
}

}  // namespace

CrossCheck cross_check(const Accelerator& a, const Accelerator& b, const RaySets& rays, WorkerPool& pool,
                       float tolerance) {
  CrossCheck check;
  check.tolerance = tolerance;
  check.width = rays.width;
  check.height = rays.height;
  check.pixel.assign(static_cast<std::size_t>(rays.width) * static_cast<std::size_t>(rays.height), Verdict::Agree);
  check_set(rays.camera, false, a, b, pool, tolerance, check.camera, check.pixel);
  check_set(rays.shadow, true, a, b, pool, tolerance, check.shadow, check.pixel);
  check_set(rays.diffuse, false, a, b, pool, tolerance, check.diffuse, check.pixel);
  return check;
}

Image disagreement_image(const CrossCheck& check, const RaySets& rays, const SceneGeometry& geometry,
                         const Accelerator& a, WorkerPool& pool) {
  Image image(check.width, check.height);
  pool.run([&] {
    tbb::parallel_for(std::size_t{0}, rays.camera.rays.size(), [&](std::size_t i) {
      const Ray& ray = rays.camera.rays[i];
      Hit hit;
      float grey = 0.02f;
      if (a.intersect(ray, hit)) {
        const SurfaceGeometry sg = surface(geometry.shapes[hit.shape], hit.prim, ray, PrimHit{hit.t, hit.uv});
        grey = 0.1f + 0.5f * std::fabs(dot(sg.ng, normalize(ray.dir)));
      }
      RGB c(grey, grey, grey);
      switch (check.pixel[rays.camera.pixel[i]]) {
        case Verdict::Agree: break;
        case Verdict::Tie: c = RGB(0.1f, 0.3f, 1.0f); break;
        case Verdict::Distance: c = RGB(1.0f, 0.85f, 0.0f); break;
        case Verdict::HitMiss: c = RGB(1.0f, 0.0f, 0.0f); break;
      }
      image.pixels[rays.camera.pixel[i]] = c;
    });
  });
  return image;
}

}  // namespace pt::bench

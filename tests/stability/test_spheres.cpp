// Spheres through every backend: tiny spheres seen from far away, huge spheres
// seen from close by, and rays starting inside, against the exact distance
// computed in long double. (The routine alone: tests/geometry/test_sphere.cpp.)
#include <gtest/gtest.h>

#include <cmath>

#include "backends.h"
#include "stability_util.h"

namespace pt {
namespace {

using Spheres = test::PerBackend;

// Nearest t > tmin along the ray to the sphere, in long double; NaN if it misses.
long double exact_t(const Sphere& s, const Ray& r) {
  long double oc[3], d[3];
  for (int i = 0; i < 3; ++i) {
    oc[i] = static_cast<long double>(r.origin[i]) - s.center[i];
    d[i] = r.dir[i];
  }
  const long double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const long double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
  const long double c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] -
                        static_cast<long double>(s.radius) * s.radius;
  const long double disc = b * b - a * c;
  if (disc < 0) return NAN;
  const long double root = std::sqrt(disc);
  const long double t0 = (-b - root) / a, t1 = (-b + root) / a;
  if (t0 > r.tmin) return t0;
  if (t1 > r.tmin) return t1;
  return NAN;
}

struct Case {
  const char* name;
  Sphere sphere;
  float distance;  // of the ray origins from the centre (< radius: inside)
};

TEST_P(Spheres, DistancesAreAccurateAtEveryScale) {
  const Case cases[] = {
      {"tiny, far away", {{3, -2, 1}, 1e-3f}, 1e4f},
      {"tiny, very far away", {{0.5f, 0.25f, 0}, 1e-2f}, 1e5f},
      {"huge, close by", {{0, 0, -1e6f - 1}, 1e6f}, 1e6f + 1},
      {"huge, far from the origin", {{1e5f, 2e5f, -3e5f}, 1e4f}, 1e4f + 0.5f},
      {"unit, inside", {{0.3f, -0.2f, 0.1f}, 1}, 0.5f},
      {"tiny, inside", {{7, 7, 7}, 1e-4f}, 5e-5f},
      {"huge, inside", {{-1e4f, 0, 0}, 1e6f}, 3e5f},
  };
  WorkerPool pool(2);
  test::Rng rng(7101);
  for (const Case& c : cases) {
    SceneGeometry g;
    g.shapes.push_back(c.sphere);
    std::unique_ptr<Accelerator> accel;
    build(g, pool, accel);
    if (!accel) return;
    const Sphere& s = c.sphere;
    int misses = 0, inaccurate = 0;
    for (int i = 0; i < 2000; ++i) {
      // Outside: aim at a point of the sphere's central disc (80% of its radius);
      // inside: any direction.
      const Vec3f origin = s.center + c.distance * rng.unit_vector();
      Vec3f dir = rng.unit_vector();
      if (c.distance > s.radius) {
        Vec3f t, b;
        const Vec3f towards = normalize(s.center - origin);
        orthonormal_basis(towards, t, b);
        const float u = rng.uniform(-0.56f, 0.56f), v = rng.uniform(-0.56f, 0.56f);
        dir = normalize(s.center + s.radius * (u * t + v * b) - origin);
      }
      const Ray ray{origin, dir};
      const long double want = exact_t(s, ray);
      if (std::isnan(want)) continue;  // the origin rounded to just outside, looking away
      Hit hit;
      if (!accel->intersect(ray, hit) || !accel->occluded(ray)) {
        ++misses;
        continue;
      }
      // Error allowed: a few ulps of the distance, plus the float rounding of
      // the sphere itself (its centre and radius) at its scale.
      const long double tolerance = 1e-5L * want + 8 * 6e-8L * (max_component(abs(s.center)) + s.radius);
      if (!(std::fabs(static_cast<long double>(hit.t) - want) <= tolerance)) {
        if (inaccurate++ < 3) ADD_FAILURE() << c.name << ": t " << hit.t << ", exact " << static_cast<double>(want);
      }
    }
    EXPECT_EQ(misses, 0) << c.name;
    EXPECT_EQ(inaccurate, 0) << c.name;
  }
}

TEST_P(Spheres, TangentRaysNeverProduceNaN) {
  const Sphere s{{10, -3, 2}, 2.5f};
  SceneGeometry g;
  g.shapes.push_back(s);
  WorkerPool pool(1);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  test::Rng rng(7102);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    // A ray whose closest approach to the centre is the radius, to within rounding.
    const Vec3f n = rng.unit_vector();
    Vec3f t, b;
    orthonormal_basis(n, t, b);
    const Vec3f touch = s.center + s.radius * n;
    const Ray ray{touch - 7.0f * t, t};
    Hit hit;
    if (accel->intersect(ray, hit)) {
      ++hits;
      ASSERT_TRUE(std::isfinite(hit.t));
      EXPECT_NEAR(hit.t, 7.0f, 0.05f);
      const SurfaceGeometry sg = surface(g.shapes[0], hit.prim, ray, PrimHit{hit.t, hit.uv});
      EXPECT_TRUE(is_finite(sg.p) && is_finite(sg.ng) && std::isfinite(sg.uv.x) && std::isfinite(sg.uv.y));
    }
  }
  RecordProperty("tangent_hits", hits);
}

INSTANTIATE_TEST_SUITE_P(Backends, Spheres, ::testing::ValuesIn(accel_kind_names()), test::backend_test_name);

}  // namespace
}  // namespace pt

// Degenerate shapes through every backend: zero-area triangles (coincident or
// collinear corners) inside an ordinary mesh, zero-area quads, zero-radius
// spheres and cylinders, coincident cylinder end points: never hit, never NaN.
// Needle triangles (a width of 1e-7 of their length): hits only where the
// needle is, with finite distance, barycentrics and normal. The hit's surface
// point (from its barycentrics) is on the needle for every backend; so is
// ray.at(t) with our triangle routine, while Embree's Plücker test computes t
// from the plane of the needle, whose normal it gets from nearly parallel
// edges: its t is approximate (the test prints how far off).
// (The routines alone: DegenerateTrianglesNeverHit etc. in tests/geometry.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

#include "backends.h"
#include "stability_util.h"

namespace pt {
namespace {

using Degenerate = test::PerBackend;

// Ids of the degenerate objects in `degenerate_scene`, and of the degenerate
// triangles inside its mesh (object 0).
const std::set<uint32_t> kDegenerateObjects = {1, 2, 3, 4, 5, 6};
const std::set<uint32_t> kDegenerateTriangles = {1, 2, 3, 5};

SceneGeometry degenerate_scene() {
  SceneGeometry g;
  TriangleMesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0},  // a unit square in z = 0
                 {0.5f, 0.5f, 0}, {0.2f, 0.2f, 0}, {-0.4f, -0.4f, 0}};
  m.indices = {0, 1, 2,   // 0: ordinary
               4, 4, 4,   // 1: three coincident corners
               4, 5, 6,   // 2: collinear corners (on the diagonal, exactly)
               0, 0, 2,   // 3: two coincident corners
               0, 2, 3,   // 4: ordinary
               6, 4, 5};  // 5: collinear, another order
  g.shapes.push_back(std::move(m));
  g.shapes.push_back(Quad{{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {3, 0, 1}}});   // 1: collinear corners
  g.shapes.push_back(Quad{{{0, 0, 2}, {0, 0, 2}, {0, 0, 2}, {0, 0, 2}}});   // 2: a point
  g.shapes.push_back(Sphere{{0, 0, 3}, 0.0f});                              // 3: zero radius
  g.shapes.push_back(Cylinder{{0, -1, 4}, {0, 1, 4}, 0.0f});                // 4: zero radius
  g.shapes.push_back(Cylinder{{0, 0, 5}, {0, 0, 5}, 1.0f});                 // 5: coincident end points
  g.shapes.push_back(Quad{{{-1, -1, 6}, {1, 1, 6}, {-1, -1, 6}, {1, 1, 6}}});  // 6: a folded segment
  return g;
}

TEST_P(Degenerate, ShapesWithoutAreaAreNeverHit) {
  const SceneGeometry g = degenerate_scene();
  WorkerPool pool(2);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  test::Rng rng(7201);
  int mesh_hits = 0;
  for (int i = 0; i < 50000; ++i) {
    // From all around, aimed at the degenerate shapes' points and lines.
    const Vec3f target{rng.uniform(-1.2f, 1.2f), rng.uniform(-1.2f, 1.2f), static_cast<float>(i % 7)};
    const Vec3f snapped = i % 3 == 0 ? Vec3f(target.x, target.x, target.z)                // the diagonal
                        : i % 3 == 1 ? Vec3f(std::round(target.x * 2) / 2, 0, target.z)  // segment points
                                     : target;
    const Vec3f origin = snapped + 3.0f * rng.unit_vector();
    const Ray ray{origin, snapped - origin};
    Hit hit;
    if (!accel->intersect(ray, hit)) continue;
    ASSERT_TRUE(std::isfinite(hit.t) && std::isfinite(hit.uv.x) && std::isfinite(hit.uv.y));
    EXPECT_FALSE(kDegenerateObjects.count(hit.shape)) << "object " << hit.shape;
    if (hit.shape == 0) {
      ++mesh_hits;
      EXPECT_FALSE(kDegenerateTriangles.count(hit.prim)) << "triangle " << hit.prim;
      const SurfaceGeometry sg = surface(g.shapes[0], hit.prim, ray, PrimHit{hit.t, hit.uv});
      EXPECT_TRUE(is_finite(sg.p) && is_finite(sg.ng) && is_finite(sg.ns));
    }
  }
  EXPECT_GT(mesh_hits, 1000);  // the ordinary triangles around them are hit
}

TEST_P(Degenerate, NeedleTrianglesGiveFiniteHitsOnlyOnTheNeedle) {
  SceneGeometry g;
  TriangleMesh m;
  test::Rng rng(7202);
  for (int i = 0; i < 200; ++i) {
    const Vec3f a{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)};
    const Vec3f along = rng.unit_vector();
    Vec3f side, unused;
    orthonormal_basis(along, side, unused);
    const float len = test::log_uniform(rng, -2, 1);
    m.positions.push_back(a);
    m.positions.push_back(a + len * along);
    m.positions.push_back(a + 0.5f * len * along + 1e-7f * len * side);
    for (uint32_t k = 0; k < 3; ++k) m.indices.push_back(static_cast<uint32_t>(3 * i) + k);
  }
  g.shapes.push_back(m);
  WorkerPool pool(2);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  int hits = 0, t_off = 0;
  float worst_t = 0.0f;  // largest distance of ray.at(t) from the needle, relative to 1 + its length
  for (int i = 0; i < 20000; ++i) {
    const uint32_t tri = static_cast<uint32_t>(test::pick(rng, 200));
    const Vec3f a = m.positions[3 * tri], b = m.positions[3 * tri + 1];
    const Vec3f target = a + rng.uniform() * (b - a);
    const Vec3f origin = target + 2.0f * rng.unit_vector();
    const Ray ray{origin, target - origin};
    Hit hit;
    if (!accel->intersect(ray, hit)) continue;
    ++hits;
    ASSERT_TRUE(std::isfinite(hit.t) && std::isfinite(hit.uv.x) && std::isfinite(hit.uv.y));
    const SurfaceGeometry sg = surface(g.shapes[0], hit.prim, ray, PrimHit{hit.t, hit.uv});
    ASSERT_TRUE(is_finite(sg.p) && is_finite(sg.ng));
    EXPECT_NEAR(length(sg.ng), 1.0f, 1e-3f);
    EXPECT_GT(hit.t, 0.0f);
    // The hit lies on the needle it reports, within rounding.
    const Vec3f p0 = m.positions[3 * hit.prim], p1 = m.positions[3 * hit.prim + 1];
    const Vec3f axis = normalize(p1 - p0);
    const float limit = 1e-4f * (1.0f + length(p1 - p0));
    auto off_axis = [&](Vec3f p) {
      const Vec3f rel = p - p0;
      return length(rel - dot(rel, axis) * axis);
    };
    EXPECT_LE(off_axis(sg.p), limit);
    const float t_error = off_axis(ray.at(hit.t));
    if (!embree_triangles()) {
      EXPECT_LE(t_error, limit);
    }
    t_off += t_error > limit ? 1 : 0;
    worst_t = std::max(worst_t, t_error / (1.0f + length(p1 - p0)));
  }
  RecordProperty("needle_hits", hits);
  std::cout << "[ needles  ] " << GetParam() << ": " << hits << " hits, " << t_off
            << " with ray.at(t) off the needle, worst " << worst_t << " x (1 + length)\n";
}

INSTANTIATE_TEST_SUITE_P(Backends, Degenerate, ::testing::ValuesIn(accel_kind_names()), test::backend_test_name);

}  // namespace
}  // namespace pt

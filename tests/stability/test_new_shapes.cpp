// The awkward rays of test_rays.cpp on the shapes added with issue 15: discs,
// convex polygons, cones and infinite planes (the plane through the layer
// above both backends, accel/unbounded.h). Axis-parallel rays with signed
// zeros, grazing rays in a shape's plane, and rays starting exactly on one.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "backends.h"
#include "stability_util.h"

namespace pt {
namespace {

using NewShapeRays = test::PerBackend;

// Each along its own stretch of the z axis, facing +z, inside [-1, 1]^2:
// 0 a disc at z = 0, 1 a hexagon at z = 10, 2 a truncated cone from z = 20
// (radius 1) to 22 (radius 0.5), 3 an annulus at z = 30; 4 an infinite plane
// x = -50 facing +x (off every ray's path but the grazing ones).
SceneGeometry new_shapes_scene() {
  SceneGeometry g;
  g.shapes.push_back(make_disc({0, 0, 0}, {0, 0, 1}, 1.0f, 0.0f));
  std::vector<Vec3f> hex;
  for (int k = 0; k < 6; ++k) hex.push_back({std::cos(k * kPi / 3), std::sin(k * kPi / 3), 10.0f});
  g.shapes.push_back(make_polygon(hex));
  g.shapes.push_back(Cone{{0, 0, 20}, {0, 0, 22}, 1.0f, 0.5f});
  g.shapes.push_back(make_disc({0, 0, 30}, {0, 0, 1}, 1.0f, 0.0625f));
  g.shapes.push_back(make_plane({-50, 0, 0}, {1, 0, 0}, {}, 1.0f));
  return g;
}

TEST_P(NewShapeRays, AxisParallelRaysWithSignedZeros) {
  const SceneGeometry g = new_shapes_scene();
  WorkerPool pool(1);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  int checked = 0;
  for (const float front : {0.0f, 10.0f, 20.0f, 30.0f}) {
    for (const float zx : {0.0f, -0.0f}) {
      for (const float zy : {0.0f, -0.0f}) {
        for (const Vec3f xy : {Vec3f(0.125f, 0, 0), Vec3f(0.25f, -0.25f, 0), Vec3f(-0.375f, 0.125f, 0)}) {
          const Ray fwd{{xy.x, xy.y, front - 3.0f}, {zx, zy, 1.0f}};
          const Ray back{{xy.x, xy.y, front + 5.0f}, {zx, zy, -1.0f}};
          for (const Ray& r : {fwd, back}) {
            Hit hit;
            ASSERT_TRUE(accel->intersect(r, hit)) << "front " << front;
            ASSERT_TRUE(accel->occluded(r));
            // The cone's top cap is at front + 2; the flat shapes at front.
            const float entry = (front == 20.0f && r.dir.z < 0) ? front + 2.0f : front;
            const float want = std::fabs(entry - r.origin.z);
            EXPECT_NEAR(hit.t, want, 1e-5f * want) << "front " << front;
            ++checked;
          }
        }
      }
    }
  }
  EXPECT_EQ(checked, 4 * 4 * 3 * 2);
  // Along -x onto the plane, other components signed zeros.
  for (const float zero : {0.0f, -0.0f}) {
    Hit hit;
    ASSERT_TRUE(accel->intersect(Ray{{-40, 5, 5}, {-1, zero, zero}}, hit));
    EXPECT_EQ(hit.shape, 4u);
    EXPECT_FLOAT_EQ(hit.t, 10.0f);
  }
}

TEST_P(NewShapeRays, GrazingRaysAreFiniteAndConsistent) {
  const SceneGeometry g = new_shapes_scene();
  WorkerPool pool(1);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  test::Rng rng(7311);
  for (const float plane_z : {0.0f, 10.0f, 20.0f, 22.0f, 30.0f}) {
    for (int i = 0; i < 2000; ++i) {
      // In the shape's plane at a random angle, or tilted by a tiny angle out of it.
      const float angle = rng.uniform(0, 2 * kPi);
      const float tilt = (i % 2) ? 0.0f : rng.uniform(-1e-6f, 1e-6f);
      Ray r;
      r.dir = {std::cos(angle), std::sin(angle), tilt};
      r.origin = Vec3f(rng.uniform(-1, 1), rng.uniform(-1, 1), plane_z) - 4.0f * r.dir;
      Hit hit;
      const bool h = accel->intersect(r, hit);
      EXPECT_EQ(h, accel->occluded(r));
      if (!h) continue;
      ASSERT_TRUE(std::isfinite(hit.t) && std::isfinite(hit.uv.x) && std::isfinite(hit.uv.y));
      const SurfaceGeometry sg = surface(g.shapes[hit.shape], hit.prim, r, PrimHit{hit.t, hit.uv});
      ASSERT_TRUE(is_finite(sg.p) && is_finite(sg.ng) && is_finite(sg.ns) && std::isfinite(sg.uv.x) &&
                  std::isfinite(sg.uv.y));
      if (hit.shape == 4) continue;  // the plane, far off
      EXPECT_LE(std::fabs(sg.p.x), 1.0f + 1e-4f);
      EXPECT_LE(std::fabs(sg.p.y), 1.0f + 1e-4f);
    }
  }
}

TEST_P(NewShapeRays, RaysStartingExactlyOnAFlatShapeNeverReHitIt) {
  const SceneGeometry g = new_shapes_scene();
  WorkerPool pool(1);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  test::Rng rng(7312);
  int rays = 0;
  for (const uint32_t shape : {0u, 1u, 3u, 4u}) {
    for (int i = 0; i < 2000; ++i) {
      // A point exactly on the shape (coordinates exact in float), leaving either side.
      Vec3f p, n;
      if (shape == 4) {
        p = {-50.0f, rng.uniform(-20, 20), rng.uniform(-20, 20)};
        n = {1, 0, 0};
      } else {
        const float z = shape == 0 ? 0.0f : (shape == 1 ? 10.0f : 30.0f);
        p = {rng.uniform(-0.6f, 0.6f), rng.uniform(-0.6f, 0.6f), z};
        if (shape == 3 && std::fabs(p.x) < 0.1f && std::fabs(p.y) < 0.1f) p.x = 0.5f;  // not in the hole
        n = {0, 0, 1};
      }
      for (const float side : {1.0f, -1.0f}) {
        const Vec3f w = rng.hemisphere(side * n, 1e-3f);
        Hit hit;
        if (accel->intersect(Ray{p, w}, hit)) {
          EXPECT_NE(hit.shape, shape) << "t " << hit.t;
        }
        ++rays;
      }
    }
  }
  EXPECT_EQ(rays, 16000);
}

INSTANTIATE_TEST_SUITE_P(Backends, NewShapeRays, ::testing::ValuesIn(accel_kind_names()), test::backend_test_name);

}  // namespace
}  // namespace pt

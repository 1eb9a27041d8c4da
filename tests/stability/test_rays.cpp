// Awkward rays through every backend and every shape type: directions parallel
// to an axis with +0 and -0 in the other components, grazing rays in the plane
// of a face, rays starting exactly on a box face, denormal inputs (inside the
// worker pool, where FTZ/DAZ are set), and NaN or infinity anywhere in a ray.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include "backends.h"
#include "stability_util.h"

namespace pt {
namespace {

using AwkwardRays = test::PerBackend;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kDenormal = 1e-40f;

// One object of each type, each alone along its own stretch of the z axis:
// object 0 a box mesh, 1..6 a box of quads, 7 a sphere, 8 a cylinder along z,
// each filling [-1, 1]^2 x [front, front + 2].
constexpr float kMeshBoxZ = 0, kQuadBoxZ = 10, kSphereZ = 20, kCylinderZ = 30;

SceneGeometry every_type_scene() {
  SceneGeometry g;
  g.shapes.push_back(test::make_box_mesh({-1, -1, kMeshBoxZ}, {1, 1, kMeshBoxZ + 2}));
  for (int f = 0; f < 6; ++f) g.shapes.push_back(test::box_face_quad({-1, -1, kQuadBoxZ}, {1, 1, kQuadBoxZ + 2}, f));
  g.shapes.push_back(Sphere{{0, 0, kSphereZ + 1}, 1.0f, {0, 0, 1}});
  g.shapes.push_back(Cylinder{{0, 0, kCylinderZ}, {0, 0, kCylinderZ + 2}, 1.0f});
  return g;
}

TEST_P(AwkwardRays, AxisParallelRaysWithSignedZeros) {
  const SceneGeometry g = every_type_scene();
  WorkerPool pool(1);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  int checked = 0;
  for (const float front : {kMeshBoxZ, kQuadBoxZ, kSphereZ, kCylinderZ}) {
    for (const float zx : {0.0f, -0.0f}) {
      for (const float zy : {0.0f, -0.0f}) {
        // Along +z from in front, and along -z from behind; x, y on a grid of
        // points inside the footprint (the centre, and off-centre points).
        for (const Vec3f xy : {Vec3f(0, 0, 0), Vec3f(0.25f, -0.5f, 0), Vec3f(-0.5f, 0.125f, 0)}) {
          const Ray fwd{{xy.x, xy.y, front - 3.0f}, {zx, zy, 1.0f}};
          const Ray back{{xy.x, xy.y, front + 5.0f}, {zx, zy, -1.0f}};
          for (const Ray& r : {fwd, back}) {
            Hit hit;
            ASSERT_TRUE(accel->intersect(r, hit)) << "front " << front;
            ASSERT_TRUE(accel->occluded(r));
            const float entry = r.dir.z > 0 ? front : front + 2.0f;
            float want = std::fabs(entry - r.origin.z);
            if (front == kSphereZ) {  // the sphere's surface lies inside its box
              want += 1.0f - std::sqrt(1.0f - xy.x * xy.x - xy.y * xy.y);
            }
            EXPECT_NEAR(hit.t, want, 1e-5f * want) << "front " << front;
            ++checked;
          }
        }
        // Along x and y (other components signed zeros), through the side of each object.
        for (int axis = 0; axis < 2; ++axis) {
          Vec3f o{0, 0, front + 1.0f}, d{zx, zy, 0.0f};
          o[axis] = -4.0f;
          d[axis] = 1.0f;
          Hit hit;
          ASSERT_TRUE(accel->intersect(Ray{o, d}, hit)) << "front " << front << " axis " << axis;
          EXPECT_NEAR(hit.t, 3.0f, 1e-5f) << "front " << front << " axis " << axis;
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 4 * 4 * (3 * 2 + 2));
}

TEST_P(AwkwardRays, GrazingRaysAreFiniteAndConsistent) {
  const SceneGeometry g = every_type_scene();
  WorkerPool pool(1);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  test::Rng rng(7301);
  for (const float front : {kMeshBoxZ, kQuadBoxZ, kCylinderZ}) {
    for (int i = 0; i < 2000; ++i) {
      // In the plane of a face (y = 1, or the front z plane), at a random
      // angle within that plane, or tilted by a tiny angle out of it.
      const bool top = i % 2 == 0;
      const float angle = rng.uniform(0, 2 * kPi);
      const float tilt = (i % 4 < 2) ? 0.0f : rng.uniform(-1e-6f, 1e-6f);
      Ray r;
      if (top) {
        r.origin = {rng.uniform(-1, 1), 1.0f, front + rng.uniform(0, 2)};
        r.dir = {std::cos(angle), tilt, std::sin(angle)};
        r.origin = r.origin - 4.0f * r.dir;
      } else {
        r.origin = {rng.uniform(-1, 1), rng.uniform(-1, 1), front};
        r.dir = {std::cos(angle), std::sin(angle), tilt};
        r.origin = r.origin - 4.0f * r.dir;
      }
      Hit hit;
      const bool h = accel->intersect(r, hit);
      EXPECT_EQ(h, accel->occluded(r));
      if (!h) continue;
      ASSERT_TRUE(std::isfinite(hit.t) && std::isfinite(hit.uv.x) && std::isfinite(hit.uv.y));
      const SurfaceGeometry sg = surface(g.shapes[hit.shape], hit.prim, r, PrimHit{hit.t, hit.uv});
      ASSERT_TRUE(is_finite(sg.p) && is_finite(sg.ng) && is_finite(sg.ns));
      // A hit on the object aimed at lies within rounding of its box (the ray
      // may go on to the objects further along z).
      const Vec3f p = r.at(hit.t);
      if (std::fabs(p.z - front - 1.0f) > 3.0f) continue;
      EXPECT_LE(std::fabs(p.x), 1.0f + 1e-4f);
      EXPECT_LE(std::fabs(p.y), 1.0f + 1e-4f);
      EXPECT_GE(p.z, front - 1e-4f);
      EXPECT_LE(p.z, front + 2.0f + 1e-4f);
    }
  }
}

TEST_P(AwkwardRays, RaysStartingExactlyOnABoxFace) {
  const SceneGeometry g = every_type_scene();
  WorkerPool pool(1);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  test::Rng rng(7302);
  int inward = 0;
  for (const float front : {kMeshBoxZ, kQuadBoxZ}) {
    for (int i = 0; i < 3000; ++i) {
      // A point exactly on one of the six faces (coordinates exact in float).
      const int face = i % 6;
      Vec3f p{rng.uniform(-0.9f, 0.9f), rng.uniform(-0.9f, 0.9f), front + 1.0f + rng.uniform(-0.9f, 0.9f)};
      Vec3f n{0, 0, 0};
      const int axis = face / 2;
      const float side = face % 2 ? 1.0f : -1.0f;
      n[axis] = side;
      p[axis] = axis == 2 ? front + 1.0f + side : side;
      const Vec3f w = rng.hemisphere(n, 1e-3f);  // outward
      Hit hit;
      // Outward: nothing but the other objects far along z; never this box.
      if (accel->intersect(Ray{p, w}, hit)) {
        const bool same_box = front == kMeshBoxZ ? hit.shape == 0 : (hit.shape >= 1 && hit.shape <= 6);
        EXPECT_FALSE(same_box) << "face " << face << " t " << hit.t;
      }
      // Inward: the opposite side of the box, not the face it starts on.
      ASSERT_TRUE(accel->intersect(Ray{p, -w}, hit)) << "face " << face;
      const Vec3f q = p - hit.t * w;
      EXPECT_GT(length(q - p), 1e-3f) << "face " << face << " re-hit at t " << hit.t;
      ++inward;
    }
  }
  EXPECT_EQ(inward, 6000);
}

// Denormals: inside the pool (FTZ/DAZ) a denormal input reads as zero, so a ray
// with denormal components answers exactly like the same ray with zeros, in
// every worker thread; no NaN, no slow path.
TEST_P(AwkwardRays, DenormalInputsBehaveAsZeros) {
  SceneGeometry g = every_type_scene();
  // And shapes with denormal coordinates.
  g.shapes.push_back(Sphere{{kDenormal, -kDenormal, 40}, 1.0f});
  TriangleMesh m;
  m.positions = {{-1, -1, 45 + kDenormal}, {1, -1, 45}, {0, 1, 45 - kDenormal}};
  m.indices = {0, 1, 2};
  g.shapes.push_back(m);
  WorkerPool pool(2);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  test::Rng rng(7303);
  std::vector<Ray> denormal, zeroed;
  for (int i = 0; i < 20000; ++i) {
    Ray r{{rng.uniform(-0.9f, 0.9f), rng.uniform(-0.9f, 0.9f), -5.0f}, {0, 0, 1}};
    Ray z = r;
    // Denormal in one or two direction components, or the origin.
    const int k = i % 4;
    if (k == 0) r.dir.x = kDenormal;
    if (k == 1) r.dir = {-kDenormal, kDenormal, 1};
    if (k == 2) {
      r.origin.x = kDenormal;
      z.origin.x = 0;
    }
    if (k == 3) {  // a direction that is all denormal
      r.dir = {kDenormal, 0, kDenormal};
      z.dir = {0, 0, 0};
    }
    denormal.push_back(r);
    zeroed.push_back(z);
  }
  std::atomic<int> mismatches{0}, without_ftz{0}, non_finite{0};
  pool.run([&] {
    tbb::parallel_for(std::size_t{0}, denormal.size(), [&](std::size_t i) {
      if (!flush_to_zero_enabled()) ++without_ftz;
      Hit a, b;
      const bool ha = accel->intersect(denormal[i], a), hb = accel->intersect(zeroed[i], b);
      if (ha != hb || (ha && (a.shape != b.shape || a.t != b.t))) ++mismatches;
      if (ha && !std::isfinite(a.t)) ++non_finite;
      if (accel->occluded(denormal[i]) != accel->occluded(zeroed[i])) ++mismatches;
    });
  });
  EXPECT_EQ(without_ftz.load(), 0);
  EXPECT_EQ(mismatches.load(), 0);
  EXPECT_EQ(non_finite.load(), 0);
}

TEST_P(AwkwardRays, NonFiniteRaysMissWithoutCrashingOrHanging) {
  const SceneGeometry g = every_type_scene();
  WorkerPool pool(1);
  std::unique_ptr<Accelerator> accel;
  build(g, pool, accel);
  if (!accel) return;
  const float inf = kInfinity;
  const Vec3f o{0.1f, 0.2f, -5.0f}, d{0, 0, 1};  // a ray that hits the mesh box at t = 5
  std::vector<Ray> rays;
  for (const float bad : {kNaN, inf, -inf}) {
    for (int c = 0; c < 3; ++c) {
      Ray r{o, d};
      r.origin[c] = bad;
      rays.push_back(r);
      r = Ray{o, d};
      r.dir[c] = bad;
      rays.push_back(r);
    }
  }
  for (const float tmin : {kNaN, inf}) rays.push_back(Ray{o, d, tmin, inf});
  for (const float tmax : {kNaN, -inf}) rays.push_back(Ray{o, d, 0.0f, tmax});
  rays.push_back(Ray{o, {0, 0, 0}});              // zero direction
  rays.push_back(Ray{o, {-0.0f, 0.0f, -0.0f}});   // signed zero direction
  rays.push_back(Ray{o, d, 7.0f, 6.0f});          // empty interval
  rays.push_back(Ray{o, d, 5.0f, 5.0f});          // empty open interval, at the hit
  rays.push_back(Ray{{kNaN, kNaN, kNaN}, {kNaN, kNaN, kNaN}, kNaN, kNaN});
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Hit hit;
    EXPECT_FALSE(accel->intersect(rays[i], hit)) << "ray " << i;
    EXPECT_FALSE(accel->occluded(rays[i])) << "ray " << i;
  }
  // The finite version of the ray hits, and an unbounded interval is fine.
  Hit hit;
  EXPECT_TRUE(accel->intersect(Ray{o, d}, hit));
  EXPECT_TRUE(accel->intersect(Ray{o, d, -inf, inf}, hit));  // a negative tmin counts as 0
  EXPECT_FLOAT_EQ(hit.t, 5.0f);
  // Huge but finite values (beyond what Embree accepts, 1.8e18): no crash, no
  // hit is invented, nothing overflows into NaN. Whether the ones aimed at the
  // scene hit is backend-dependent (Embree answers a miss).
  EXPECT_FALSE(accel->intersect(Ray{{3e38f, 0, 0}, {1, 0, 0}}, hit));
  EXPECT_FALSE(accel->occluded(Ray{{3e38f, 0, 0}, {1, 0, 0}}));
  for (const Ray& r : {Ray{{0.1f, 0.2f, -3e38f}, {0, 0, 1}}, Ray{{0.1f, 0.2f, -5.0f}, {0, 0, 3e38f}},
                       Ray{{0.1f, 0.2f, -5.0f}, {0, 0, 1e-30f}}, Ray{{0.1f, 0.2f, -1e19f}, {0, 0, 1e19f}}}) {
    const bool occluded = accel->occluded(r);
    if (accel->intersect(r, hit)) {
      EXPECT_TRUE(std::isfinite(hit.t));
      EXPECT_TRUE(occluded);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, AwkwardRays, ::testing::ValuesIn(accel_kind_names()), test::backend_test_name);

}  // namespace
}  // namespace pt

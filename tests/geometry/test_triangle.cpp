#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/shapes.h"
#include "test_util.h"

namespace pt {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

const Vec3f kP0{0, 0, 0}, kP1{1, 0, 0}, kP2{0, 1, 0};

TEST(Triangle, HitReturnsDistanceAndBarycentrics) {
  PrimHit hit;
  ASSERT_TRUE(intersect_triangle(kP0, kP1, kP2, Ray{{0.2f, 0.3f, 2}, {0, 0, -1}}, hit));
  EXPECT_FLOAT_EQ(hit.t, 2.0f);
  EXPECT_NEAR(hit.uv.x, 0.2f, 1e-6f);  // weight of p1
  EXPECT_NEAR(hit.uv.y, 0.3f, 1e-6f);  // weight of p2
  // Either winding, either side.
  ASSERT_TRUE(intersect_triangle(kP0, kP2, kP1, Ray{{0.2f, 0.3f, -1}, {0, 0, 1}}, hit));
  EXPECT_FLOAT_EQ(hit.t, 1.0f);
  EXPECT_NEAR(hit.uv.x, 0.3f, 1e-6f);
}

TEST(Triangle, MissesOutsideAndParallel) {
  PrimHit hit;
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{{0.6f, 0.6f, 1}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{{-0.01f, 0.5f, 1}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{{0.2f, 0.2f, 1}, {1, 0, 0}}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{{-1, 0.2f, 0}, {1, 0, 0}}, hit));  // in-plane
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{{-1, 0, 0}, {1, 0, 0}}, hit));     // along an edge
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{{0.2f, 0.2f, 1}, {0, 0, 1}}, hit)); // behind
}

TEST(Triangle, DegenerateTrianglesNeverHit) {
  PrimHit hit;
  const Vec3f a{0, 0, 0}, b{1, 1, 1}, c{2, 2, 2};
  test::Rng rng(1);
  for (int i = 0; i < 5000; ++i) {
    // Rays through random points of the degenerate triangles' lines/points.
    const Vec3f on_line = rng.uniform(0.0f, 2.0f) * b;
    const Vec3f origin = on_line + 3.0f * rng.unit_vector();
    const Ray ray{origin, on_line - origin};
    EXPECT_FALSE(intersect_triangle(a, b, c, ray, hit));
    EXPECT_FALSE(intersect_triangle(a, a, b, ray, hit));
    EXPECT_FALSE(intersect_triangle(b, b, b, Ray{origin, b - origin}, hit));
  }
}

TEST(Triangle, NonFiniteRaysNeverHit) {
  PrimHit hit;
  const Vec3f o{0.2f, 0.2f, 1};
  const Vec3f d{0, 0, -1};
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{{kNaN, 0.2f, 1}, d}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{o, {0, kNaN, -1}}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{{0.2f, 0.2f, kInfinity}, d}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{o, {0, 0, -kInfinity}}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{o, {kInfinity, kInfinity, -kInfinity}}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{o, {0, 0, 0}}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{o, d, kNaN, kInfinity}, hit));
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, Ray{o, d, 0.0f, kNaN}, hit));
}

TEST(Triangle, RaysAlongEachAxisIncludingNegativeZero) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    Vec3f p0(0.0f), p1(0.0f), p2(0.0f);
    p0[u] = -1;
    p0[v] = -1;
    p1[u] = 2;
    p1[v] = -1;
    p2[u] = -1;
    p2[v] = 2;
    for (float sign : {1.0f, -1.0f}) {
      Vec3f o(-0.0f), d(-0.0f);
      o[axis] = -3.0f * sign;
      d[axis] = sign;
      PrimHit hit;
      ASSERT_TRUE(intersect_triangle(p0, p1, p2, Ray{o, d}, hit)) << axis;
      EXPECT_FLOAT_EQ(hit.t, 3.0f);
      EXPECT_NEAR(hit.uv.x, 1.0f / 3.0f, 1e-6f);
      EXPECT_NEAR(hit.uv.y, 1.0f / 3.0f, 1e-6f);
    }
  }
}

TEST(Triangle, IntervalIsOpenOnBothEnds) {
  PrimHit hit;
  const Ray base{{0.2f, 0.2f, 3}, {0, 0, -1}};
  ASSERT_TRUE(intersect_triangle(kP0, kP1, kP2, base, hit));
  const float t = hit.t;
  EXPECT_NEAR(t, 3.0f, 1e-6f);
  Ray r = base;
  r.tmax = t;
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, r, hit));
  r.tmax = std::nextafter(t, 4.0f);
  EXPECT_TRUE(intersect_triangle(kP0, kP1, kP2, r, hit));
  r = base;
  r.tmin = t;
  EXPECT_FALSE(intersect_triangle(kP0, kP1, kP2, r, hit));
  r.tmin = std::nextafter(t, 0.0f);
  EXPECT_TRUE(intersect_triangle(kP0, kP1, kP2, r, hit));
}

TEST(Triangle, SharedEdgesAndVerticesOfAFanHaveNoCracks) {
  // A fan of triangles around a centre vertex; rays aimed exactly at the
  // centre vertex and at points of the shared edges hit at least one.
  const Vec3f centre{0.137f, -0.291f, 0.05f};
  const int n = 7;
  Vec3f ring[n];
  for (int i = 0; i < n; ++i) {
    const float a = 2.0f * kPi * static_cast<float>(i) / n;
    ring[i] = centre + Vec3f(std::cos(a), std::sin(a), 0.1f * std::sin(3.0f * a));
  }
  // The fan is not planar: a ray crosses it for sure only when it comes from
  // the side above (or below) every triangle's plane.
  Vec3f normals[n];
  for (int i = 0; i < n; ++i) normals[i] = normalize(cross(ring[i] - centre, ring[(i + 1) % n] - centre));
  auto above_all = [&](Vec3f w) {
    for (const Vec3f& nrm : normals) {
      if (dot(w, nrm) < 0.1f) return false;
    }
    return true;
  };
  test::Rng rng(9);
  int misses = 0;
  for (int k = 0; k < 20000; ++k) {
    const int e = k % n;
    const float s = (k % 3 == 0) ? 0.0f : rng.uniform();
    const Vec3f target = centre + s * (ring[e] - centre);
    Vec3f w = rng.unit_vector();
    while (!above_all(w)) w = rng.unit_vector();
    const Vec3f origin = target + 2.0f * (k % 2 ? w : -w);
    const Ray ray{origin, target - origin};
    bool any = false;
    for (int i = 0; i < n && !any; ++i) {
      PrimHit hit;
      any = intersect_triangle(centre, ring[i], ring[(i + 1) % n], ray, hit);
    }
    if (!any) ++misses;
  }
  EXPECT_EQ(misses, 0);
}

// The conservative bound on t is as scale-free as t itself: a ray from just
// inside a closed box, towards the far side, hits it however long its
// direction vector is. The short directions are the object-space rays of a
// placement scaled up ~1e4 (a unit world direction times M^-1); with
// pbrt-v4's bound, which grows as 1 / |d|^2 there against t's 1 / |d|, the
// exit through the face at t = 2979 |d0| / |d| was rejected as not certainly
// positive and the ray left the box (found by the transformed-instances
// stability test, docs/numerical-stability.md section 11).
TEST(Triangle, ExitFromInsideAClosedBoxWithShortAndLongDirections) {
  const TriangleMesh box = test::make_box_mesh({-1, -1, -1}, {1, 1, 1});
  Ray ray;
  ray.origin = Vec3f(0.443309784f, -0.927370429f, -0.999958038f);  // 4e-5 inside the face z = -1
  const Vec3f d0(3.27747694e-05f, -2.43790673e-05f, 1.62940341e-05f);
  for (float k : {1e-3f, 1.0f, 1e2f, 3e4f, 1e7f}) {
    ray.dir = d0 * k;
    int hits = 0;
    float t = 0.0f;
    for (uint32_t i = 0; i < box.triangle_count(); ++i) {
      PrimHit h;
      if (intersect(box, i, ray, h)) {
        ++hits;
        t = h.t;
      }
    }
    EXPECT_EQ(hits, 1) << "direction scaled by " << k;
    EXPECT_NEAR(t * k, 2979.18f, 0.01f) << "direction scaled by " << k;  // the face y = -1
  }
}

TEST(TriangleMesh, SurfaceInterpolatesNormalsAndUvsAndFlipsShadingNormal) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  const Ray ray{{0.25f, 0.25f, 1}, {0, 0, -1}};
  PrimHit hit;
  ASSERT_TRUE(intersect(m, 0, ray, hit));
  SurfaceGeometry sg = surface(m, 0, ray, hit);
  EXPECT_NEAR(sg.ng.z, 1.0f, 1e-6f);  // normalize(cross(p1 - p0, p2 - p0))
  EXPECT_EQ(sg.ns, sg.ng);
  EXPECT_NEAR(sg.uv.x, 0.25f, 1e-6f);  // barycentrics without per-vertex uvs
  EXPECT_NEAR(sg.uv.y, 0.25f, 1e-6f);

  // Per-vertex normals on the other side: the shading normal is flipped to ng's side.
  m.normals = {normalize(Vec3f(0.2f, 0, -1)), normalize(Vec3f(0, 0.2f, -1)), {0, 0, -1}};
  m.uvs = {{0, 0}, {2, 0}, {0, 4}};
  sg = surface(m, 0, ray, hit);
  EXPECT_GT(dot(sg.ns, sg.ng), 0.9f);
  EXPECT_NEAR(length(sg.ns), 1.0f, 1e-6f);
  EXPECT_LT(sg.ns.x, 0.0f);  // -(0.2 * 0.5 / |.|, ...) after the flip
  EXPECT_NEAR(sg.uv.x, 0.5f, 1e-6f);
  EXPECT_NEAR(sg.uv.y, 1.0f, 1e-6f);

  // Opposing normals that cancel: the shading normal falls back to ng.
  m.normals = {{0, 0, 1}, {0, 0, -1}, {0, 0, 0}};
  PrimHit mid;
  ASSERT_TRUE(intersect(m, 0, Ray{{0.5f, 0.0f + 1e-7f, 1}, {0, 0, -1}}, mid));
  mid.uv = {0.5f, 0.0f};
  sg = surface(m, 0, ray, mid);
  EXPECT_EQ(sg.ns, sg.ng);
}

TEST(TriangleMesh, BoundsCoverTheTriangle) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 2, 3}, {-1, 5, 0}, {100, 100, 100}};
  m.indices = {0, 1, 2};
  const Bounds3f b = bounds(m, 0);
  EXPECT_LE(b.lo.x, -1.0f);
  EXPECT_GE(b.hi.y, 5.0f);
  EXPECT_LT(b.hi.x, 1.01f);
  const Bounds3f all = bounds(Shape{m});
  EXPECT_LT(all.hi.x, 1.01f);  // only referenced vertices count
}

}  // namespace
}  // namespace pt

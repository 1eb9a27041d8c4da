#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/shapes.h"
#include "test_util.h"

namespace pt {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

Quad unit_square() { return Quad{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}}; }

Vec3f bilerp(const Quad& q, float u, float v) {
  return (1 - u) * (1 - v) * q.v[0] + u * (1 - v) * q.v[1] + u * v * q.v[2] + (1 - u) * v * q.v[3];
}

TEST(Quad, HitHasKnownDistanceNormalAndTextureCoordinates) {
  const Quad q = unit_square();
  const Ray ray{{0.25f, 0.75f, 2}, {0, 0, -1}};
  PrimHit hit;
  ASSERT_TRUE(intersect(q, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 2.0f);
  const SurfaceGeometry sg = surface(q, ray, hit);
  EXPECT_NEAR(sg.p.x, 0.25f, 1e-6f);
  EXPECT_NEAR(sg.p.y, 0.75f, 1e-6f);
  EXPECT_EQ(sg.p.z, 0.0f);
  EXPECT_NEAR(sg.ng.z, 1.0f, 1e-6f);  // right-handed from the corner order
  EXPECT_NEAR(sg.uv.x, 0.25f, 1e-6f); // u along v0 -> v1
  EXPECT_NEAR(sg.uv.y, 0.75f, 1e-6f); // v along v0 -> v3
}

TEST(Quad, IsDoubleSidedAndKeepsItsNormal) {
  const Quad q = unit_square();
  const Ray ray{{0.6f, 0.3f, -1}, {0, 0, 1}};
  PrimHit hit;
  ASSERT_TRUE(intersect(q, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 1.0f);
  EXPECT_NEAR(surface(q, ray, hit).ng.z, 1.0f, 1e-6f);  // not flipped towards the ray
}

TEST(Quad, TextureCoordinatesAreBilinearForAnyConvexQuad) {
  const Quad shapes[] = {
      {{{1, 2, 3}, {3, 2.5f, 3}, {3.5f, 4, 3.2f}, {1.5f, 3.5f, 3.2f}}},  // parallelogram, tilted
      {{{0, 0, 0}, {4, 0, 0}, {3, 2, 0}, {1, 2, 0}}},                    // trapezoid
      {{{0, 0, 0}, {2, 0.3f, 0}, {2.5f, 2, 0}, {-0.2f, 1.5f, 0}}},       // general convex
  };
  test::Rng rng(7);
  for (const Quad& q : shapes) {
    for (int i = 0; i < 200; ++i) {
      const float u = rng.uniform(0.01f, 0.99f);
      const float v = rng.uniform(0.01f, 0.99f);
      const Vec3f target = bilerp(q, u, v);
      const Vec3f origin = target + Vec3f(0.3f, -0.2f, 5.0f);
      const Ray ray{origin, target - origin};
      PrimHit hit;
      ASSERT_TRUE(intersect(q, ray, hit));
      EXPECT_NEAR(hit.t, 1.0f, 1e-5f);
      const SurfaceGeometry sg = surface(q, ray, hit);
      EXPECT_NEAR(sg.uv.x, u, 2e-5f);
      EXPECT_NEAR(sg.uv.y, v, 2e-5f);
      EXPECT_NEAR(length(sg.p - target), 0.0f, 2e-5f);
    }
  }
}

TEST(Quad, CornersMapToTheUnitSquare) {
  const Quad q{{{0, 0, 0}, {4, 0, 0}, {3, 2, 0}, {1, 2, 0}}};
  const Vec2f expected[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Vec3f centre = bilerp(q, 0.5f, 0.5f);
  for (int k = 0; k < 4; ++k) {
    // Aim just inside each corner.
    const Vec3f target = q.v[k] + 1e-4f * (centre - q.v[k]);
    const Ray ray{target + Vec3f(0, 0, 1), {0, 0, -1}};
    PrimHit hit;
    ASSERT_TRUE(intersect(q, ray, hit)) << k;
    const Vec2f uv = surface(q, ray, hit).uv;
    EXPECT_NEAR(uv.x, expected[k].x, 1e-3f);
    EXPECT_NEAR(uv.y, expected[k].y, 1e-3f);
  }
}

TEST(Quad, MissesOutsideAndParallel) {
  const Quad q = unit_square();
  PrimHit hit;
  EXPECT_FALSE(intersect(q, Ray{{1.001f, 0.5f, 1}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, -0.001f, 1}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, 1}, {0, 0, 1}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, 1}, {1, 0, 0}}, hit));
}

TEST(Quad, GrazingAlongAnEdgeNeverHitsOrProducesNaN) {
  const Quad q = unit_square();
  PrimHit hit;
  // In the quad's plane, along the edge v0 -> v1 and across the interior.
  EXPECT_FALSE(intersect(q, Ray{{-1, 0, 0}, {1, 0, 0}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{-1, 0.5f, 0}, {1, 0, 0}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{-1, 0, -0.0f}, {1, -0.0f, -0.0f}}, hit));
}

TEST(Quad, SharedEdgeBetweenTwoQuadsHasNoCrack) {
  // Two quads sharing the edge x = 1 at non-representable-friendly positions.
  const Quad a{{{0.1f, 0.3f, 0.7f}, {1.3f, 0.2f, 0.9f}, {1.2f, 1.7f, 1.1f}, {0.2f, 1.6f, 0.9f}}};
  const Quad b{{{1.3f, 0.2f, 0.9f}, {2.6f, 0.4f, 1.0f}, {2.4f, 1.8f, 1.3f}, {1.2f, 1.7f, 1.1f}}};
  // The quads are folded along the edge: a ray crosses the sheet for sure
  // only when it comes from the side above both planes.
  const Vec3f na = normalize(cross(a.v[2] - a.v[0], a.v[3] - a.v[1]));
  const Vec3f nb = normalize(cross(b.v[2] - b.v[0], b.v[3] - b.v[1]));
  test::Rng rng(11);
  int misses = 0;
  for (int i = 0; i < 20000; ++i) {
    const float s = rng.uniform();
    const Vec3f on_edge = (1 - s) * a.v[1] + s * a.v[2];
    Vec3f w = rng.unit_vector();
    while (dot(w, na) < 0.1f || dot(w, nb) < 0.1f) w = rng.unit_vector();
    const Vec3f origin = on_edge + 3.0f * (i % 2 ? w : -w);
    const Ray ray{origin, on_edge - origin};
    PrimHit ha, hb;
    if (!intersect(a, ray, ha) && !intersect(b, ray, hb)) ++misses;
  }
  EXPECT_EQ(misses, 0);
}

TEST(Quad, RaysAlongEachAxisIncludingNegativeZero) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    Quad q;
    for (int k = 0; k < 4; ++k) {
      q.v[k] = Vec3f(0.0f);
      q.v[k][u] = (k == 1 || k == 2) ? 1.0f : -1.0f;
      q.v[k][v] = (k >= 2) ? 1.0f : -1.0f;
    }
    for (float sign : {1.0f, -1.0f}) {
      Vec3f o(-0.0f), d(-0.0f);
      o[axis] = -2.0f * sign;
      d[axis] = sign;
      PrimHit hit;
      ASSERT_TRUE(intersect(q, Ray{o, d}, hit));
      EXPECT_FLOAT_EQ(hit.t, 2.0f);
      const SurfaceGeometry sg = surface(q, Ray{o, d}, hit);
      EXPECT_NEAR(std::fabs(sg.ng[axis]), 1.0f, 1e-6f);
      EXPECT_NEAR(sg.uv.x, 0.5f, 1e-6f);
      EXPECT_NEAR(sg.uv.y, 0.5f, 1e-6f);
    }
  }
}

TEST(Quad, DegenerateQuadsNeverHitAndNeverProduceNaN) {
  const Quad point{{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}}};
  const Quad line{{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}};
  const Quad folded{{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 0}}};
  PrimHit hit;
  for (const Quad& q : {point, line, folded}) {
    EXPECT_FALSE(intersect(q, Ray{{1, 1, 5}, {0, 0, -1}}, hit));
    EXPECT_FALSE(intersect(q, Ray{{1, 0, 5}, {0, 0, -1}}, hit));
    EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, -3}, normalize(Vec3f(0.5f, 0.5f, 3.5f))}, hit));
    EXPECT_FALSE(intersect(q, Ray{{-1, -1, -1}, {1, 1, 1}}, hit));
    const Bounds3f b = bounds(q);
    EXPECT_TRUE(is_finite(b.lo) && is_finite(b.hi));
  }
}

TEST(Quad, NonFiniteRaysNeverHit) {
  const Quad q = unit_square();
  PrimHit hit;
  EXPECT_FALSE(intersect(q, Ray{{kNaN, 0.5f, 1}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, 1}, {0, kNaN, -1}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, kInfinity}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, 1}, {0, 0, -kInfinity}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, 1}, {0, 0, 0}}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, 1}, {0, 0, -1}, kNaN, kInfinity}, hit));
  EXPECT_FALSE(intersect(q, Ray{{0.5f, 0.5f, 1}, {0, 0, -1}, 0.0f, kNaN}, hit));
}

TEST(Quad, IntervalIsOpenOnBothEnds) {
  PrimHit hit;
  const Ray base{{0.2f, 0.2f, 3}, {0, 0, -1}};
  ASSERT_TRUE(intersect(unit_square(), base, hit));
  const float t = hit.t;
  EXPECT_NEAR(t, 3.0f, 1e-6f);
  Ray r = base;
  r.tmax = t;
  EXPECT_FALSE(intersect(unit_square(), r, hit));
  r.tmax = std::nextafter(t, 4.0f);
  EXPECT_TRUE(intersect(unit_square(), r, hit));
  r = base;
  r.tmin = t;
  EXPECT_FALSE(intersect(unit_square(), r, hit));
  r.tmin = std::nextafter(t, 0.0f);
  EXPECT_TRUE(intersect(unit_square(), r, hit));
}

}  // namespace
}  // namespace pt

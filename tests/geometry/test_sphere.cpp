#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/shapes.h"

namespace pt {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(Sphere, HitFromOutsideHasKnownDistanceAndOutwardNormal) {
  const Sphere s{{0, 0, 5}, 1.0f};
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  PrimHit hit;
  ASSERT_TRUE(intersect(s, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 4.0f);
  const SurfaceGeometry sg = surface(s, ray, hit);
  EXPECT_NEAR(sg.p.z, 4.0f, 1e-6f);
  EXPECT_NEAR(sg.ng.z, -1.0f, 1e-6f);  // outward, facing the ray here
  EXPECT_EQ(sg.ns, sg.ng);
}

TEST(Sphere, UnnormalisedDirectionScalesT) {
  const Sphere s{{0, 0, 5}, 1.0f};
  PrimHit hit;
  ASSERT_TRUE(intersect(s, Ray{{0, 0, 0}, {0, 0, 2}}, hit));
  EXPECT_FLOAT_EQ(hit.t, 2.0f);
}

TEST(Sphere, MissesBesideAndBehind) {
  const Sphere s{{0, 0, 5}, 1.0f};
  PrimHit hit;
  EXPECT_FALSE(intersect(s, Ray{{1.01f, 0, 0}, {0, 0, 1}}, hit));
  EXPECT_FALSE(intersect(s, Ray{{0, 0, 0}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect(s, Ray{{0, 0, 0}, {0, 1, 0}}, hit));
}

TEST(Sphere, RayFromInsideHitsTheFarSideWithOutwardNormal) {
  const Sphere s{{1, 2, 3}, 2.0f};
  const Ray ray{{1, 2, 3}, {0, 1, 0}};
  PrimHit hit;
  ASSERT_TRUE(intersect(s, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 2.0f);
  const SurfaceGeometry sg = surface(s, ray, hit);
  EXPECT_NEAR(sg.ng.y, 1.0f, 1e-6f);  // outward: NOT flipped towards the ray
}

TEST(Sphere, TinySphereFarAwayIsAccurate) {
  const Sphere s{{0, 0, 10000}, 1e-3f};
  PrimHit hit;
  ASSERT_TRUE(intersect(s, Ray{{0, 0, 0}, {0, 0, 1}}, hit));
  EXPECT_NEAR(hit.t, 10000.0f - 1e-3f, 2e-3f);
  // Off-centre by half the radius still hits (the naive discriminant loses it).
  ASSERT_TRUE(intersect(s, Ray{{0, 0, 0}, normalize(Vec3f(0.5e-3f, 0, 10000))}, hit));
  EXPECT_NEAR(hit.t, 10000.0f, 2e-3f);
}

TEST(Sphere, HugeSphereCloseByIsAccurate) {
  const Sphere s{{0, 0, 1000001}, 1e6f};  // surface at z = 1
  PrimHit hit;
  ASSERT_TRUE(intersect(s, Ray{{0, 0, 0}, {0, 0, 1}}, hit));
  EXPECT_NEAR(hit.t, 1.0f, 1e-5f);
  ASSERT_TRUE(intersect(s, Ray{{0, 0, 0}, {0, 0, -1}}, hit) == false);
}

TEST(Sphere, TangentRayIsConsistentAndFinite) {
  const Sphere s{{0, 0, 5}, 1.0f};
  for (float x : {1.0f, std::nextafter(1.0f, 0.0f), std::nextafter(1.0f, 2.0f)}) {
    PrimHit hit;
    if (intersect(s, Ray{{x, 0, 0}, {0, 0, 1}}, hit)) {
      EXPECT_TRUE(std::isfinite(hit.t));
      EXPECT_NEAR(hit.t, 5.0f, 1e-2f);
      EXPECT_LE(x, 1.0f);
    }
  }
  PrimHit hit;
  EXPECT_FALSE(intersect(s, Ray{{1.0001f, 0, 0}, {0, 0, 1}}, hit));
  EXPECT_TRUE(intersect(s, Ray{{0.9999f, 0, 0}, {0, 0, 1}}, hit));
}

TEST(Sphere, RaysAlongEachAxisIncludingNegativeZero) {
  const Sphere s{{0, 0, 0}, 1.0f};
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      Vec3f o(-0.0f);
      o[axis] = -3.0f * sign;
      Vec3f d(-0.0f);
      d[axis] = sign;
      PrimHit hit;
      ASSERT_TRUE(intersect(s, Ray{o, d}, hit)) << axis << " " << sign;
      EXPECT_FLOAT_EQ(hit.t, 2.0f);
      const SurfaceGeometry sg = surface(s, Ray{o, d}, hit);
      EXPECT_NEAR(sg.ng[axis], -sign, 1e-6f);
    }
  }
}

TEST(Sphere, DegenerateSpheresNeverHit) {
  PrimHit hit;
  const Ray ray{{0, 0, -5}, {0, 0, 1}};
  EXPECT_FALSE(intersect(Sphere{{0, 0, 0}, 0.0f}, ray, hit));
  EXPECT_FALSE(intersect(Sphere{{0, 0, 0}, -1.0f}, ray, hit));
  EXPECT_FALSE(intersect(Sphere{{0, 0, 0}, kNaN}, ray, hit));
  EXPECT_FALSE(intersect(Sphere{{kNaN, 0, 0}, 1.0f}, ray, hit));
}

TEST(Sphere, NonFiniteRaysNeverHit) {
  const Sphere s{{0, 0, 0}, 1.0f};
  const float inf = kInfinity;
  PrimHit hit;
  EXPECT_FALSE(intersect(s, Ray{{kNaN, 0, -5}, {0, 0, 1}}, hit));
  EXPECT_FALSE(intersect(s, Ray{{0, 0, -5}, {0, kNaN, 1}}, hit));
  EXPECT_FALSE(intersect(s, Ray{{0, 0, -inf}, {0, 0, 1}}, hit));
  EXPECT_FALSE(intersect(s, Ray{{0, 0, -5}, {0, 0, inf}}, hit));
  EXPECT_FALSE(intersect(s, Ray{{0, 0, -5}, {0, 0, 0}}, hit));
  EXPECT_FALSE(intersect(s, Ray{{0, 0, -5}, {0, 0, 1}, kNaN, kInfinity}, hit));
  EXPECT_FALSE(intersect(s, Ray{{0, 0, -5}, {0, 0, 1}, 0.0f, kNaN}, hit));
}

TEST(Sphere, IntervalIsOpenOnBothEnds) {
  const Sphere s{{0, 0, 5}, 1.0f};
  PrimHit hit;
  ASSERT_TRUE(intersect(s, Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, std::nextafter(4.0f, 5.0f)}, hit));
  EXPECT_FLOAT_EQ(hit.t, 4.0f);
  EXPECT_FALSE(intersect(s, Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, 4.0f}, hit));
  // tmin == near root: the far root is the nearest valid hit.
  ASSERT_TRUE(intersect(s, Ray{{0, 0, 0}, {0, 0, 1}, 4.0f, kInfinity}, hit));
  EXPECT_FLOAT_EQ(hit.t, 6.0f);
  EXPECT_FALSE(intersect(s, Ray{{0, 0, 0}, {0, 0, 1}, 6.0f, kInfinity}, hit));
}

TEST(Sphere, LongitudeLatitudeAboutThePole) {
  const Sphere y_up{{0, 0, 0}, 1.0f, {0, 1, 0}};
  auto uv_at = [](const Sphere& s, Vec3f dir) {
    const Ray ray{s.center + 3.0f * dir, -dir};
    PrimHit hit;
    EXPECT_TRUE(intersect(s, ray, hit));
    return surface(s, ray, hit).uv;
  };
  EXPECT_NEAR(uv_at(y_up, {0, 1, 0}).y, 0.0f, 1e-3f);   // north pole
  EXPECT_NEAR(uv_at(y_up, {0, -1, 0}).y, 1.0f, 1e-3f);  // south pole
  const Vec2f plus_x = uv_at(y_up, {1, 0, 0});
  EXPECT_NEAR(plus_x.x, 0.0f, 1e-6f);  // the seam is at +x
  EXPECT_NEAR(plus_x.y, 0.5f, 1e-6f);
  EXPECT_NEAR(uv_at(y_up, {0, 0, -1}).x, 0.25f, 1e-6f);  // counter-clockwise seen from +y
  EXPECT_NEAR(uv_at(y_up, {-1, 0, 0}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(uv_at(y_up, {0, 0, 1}).x, 0.75f, 1e-6f);

  const Sphere z_up{{2, 3, 4}, 2.0f, {0, 0, 1}};
  EXPECT_NEAR(uv_at(z_up, {0, 1, 0}).x, 0.25f, 1e-6f);  // counter-clockwise seen from +z
  EXPECT_NEAR(uv_at(z_up, {0, 0, 1}).y, 0.0f, 1e-3f);
  // u stays in [0, 1) just below the seam.
  const Vec2f below_seam = uv_at(z_up, normalize(Vec3f(1, -1e-7f, 0)));
  EXPECT_GE(below_seam.x, 0.0f);
  EXPECT_LT(below_seam.x, 1.0f);
}

TEST(Sphere, SurfacePointIsReprojectedOntoTheSphere) {
  const Sphere s{{100, -50, 30}, 0.5f};
  const Ray ray{{-3000, 2000, 1000}, normalize(s.center + Vec3f(0.1f, 0.2f, 0.3f) - Vec3f(-3000, 2000, 1000))};
  PrimHit hit;
  ASSERT_TRUE(intersect(s, ray, hit));
  const SurfaceGeometry sg = surface(s, ray, hit);
  EXPECT_NEAR(length(sg.p - s.center), 0.5f, 1e-5f);
  EXPECT_NEAR(length(sg.ng), 1.0f, 1e-6f);
}

TEST(Sphere, BoundsContainTheSphere) {
  const Bounds3f b = bounds(Sphere{{1, 2, 3}, 2.0f});
  EXPECT_LE(b.lo.x, -1.0f);
  EXPECT_GE(b.hi.z, 5.0f);
  EXPECT_NEAR(b.lo.y, 0.0f, 1e-5f);
  const Bounds3f d = bounds(Sphere{{1, 2, 3}, -1.0f});
  EXPECT_FALSE(d.empty());  // degenerate: a point box, never invalid
}

}  // namespace
}  // namespace pt

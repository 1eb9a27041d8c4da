#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/shapes.h"
#include "test_util.h"

namespace pt {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

const Cylinder kZ{{0, 0, 0}, {0, 0, 2}, 1.0f};

using test::hit_surface;

TEST(Cylinder, SideHitHasOutwardNormalAndTextureCoordinates) {
  const SurfaceGeometry sg = hit_surface(kZ, Ray{{5, 0, 0.5f}, {-1, 0, 0}}, 4.0f);
  EXPECT_NEAR(sg.ng.x, 1.0f, 1e-6f);
  EXPECT_NEAR(sg.uv.x, 0.0f, 1e-6f);   // u around the axis, 0 at +x for a z axis
  EXPECT_NEAR(sg.uv.y, 0.25f, 1e-6f);  // v along the axis, p0 -> p1
  const SurfaceGeometry sy = hit_surface(kZ, Ray{{0, 5, 1.5f}, {0, -1, 0}}, 4.0f);
  EXPECT_NEAR(sy.ng.y, 1.0f, 1e-6f);
  EXPECT_NEAR(sy.uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(sy.uv.y, 0.75f, 1e-6f);
}

TEST(Cylinder, CapsAreHitWithAxialNormals) {
  const SurfaceGeometry top = hit_surface(kZ, Ray{{0.5f, 0, 5}, {0, 0, -1}}, 3.0f);
  EXPECT_NEAR(top.ng.z, 1.0f, 1e-6f);
  EXPECT_NEAR(top.p.z, 2.0f, 1e-6f);
  EXPECT_NEAR(top.uv.y, 1.0f, 1e-6f);
  const SurfaceGeometry bottom = hit_surface(kZ, Ray{{0.5f, 0.2f, -3}, {0, 0, 1}}, 3.0f);
  EXPECT_NEAR(bottom.ng.z, -1.0f, 1e-6f);
  EXPECT_NEAR(bottom.p.z, 0.0f, 1e-6f);
  EXPECT_NEAR(bottom.uv.y, 0.0f, 1e-6f);
}

TEST(Cylinder, RaysFromInsideFindTheExitWithOutwardNormal) {
  const SurfaceGeometry side = hit_surface(kZ, Ray{{0, 0, 1}, {1, 0, 0}}, 1.0f);
  EXPECT_NEAR(side.ng.x, 1.0f, 1e-6f);
  const SurfaceGeometry cap = hit_surface(kZ, Ray{{0.3f, 0, 1}, {0, 0, 1}}, 1.0f);
  EXPECT_NEAR(cap.ng.z, 1.0f, 1e-6f);
  const SurfaceGeometry down = hit_surface(kZ, Ray{{0.3f, 0, 1}, {0, 0, -2}}, 0.5f);
  EXPECT_NEAR(down.ng.z, -1.0f, 1e-6f);
}

TEST(Cylinder, MissesOutside) {
  PrimHit hit;
  EXPECT_FALSE(intersect(kZ, Ray{{1.01f, 0, 5}, {0, 0, -1}}, hit));   // parallel, outside radius
  EXPECT_FALSE(intersect(kZ, Ray{{5, 0, 2.01f}, {-1, 0, 0}}, hit));   // perpendicular, above the cap
  EXPECT_FALSE(intersect(kZ, Ray{{5, 0, -0.01f}, {-1, 0, 0}}, hit));  // below
  EXPECT_FALSE(intersect(kZ, Ray{{5, 0, 1}, {1, 0, 0}}, hit));        // pointing away
  EXPECT_FALSE(intersect(kZ, Ray{{5, 1.01f, 1}, {-1, 0, 0}}, hit));   // beside
}

TEST(Cylinder, RaysAlongEachAxisIncludingNegativeZero) {
  for (int axis = 0; axis < 3; ++axis) {
    Vec3f p1(0.0f);
    p1[axis] = 2.0f;
    const Cylinder c{{0, 0, 0}, p1, 1.0f};
    for (float sign : {1.0f, -1.0f}) {
      // Along the axis: through both caps.
      Vec3f o(-0.0f), d(-0.0f);
      o[axis] = sign > 0 ? -1.0f : 3.0f;
      d[axis] = sign;
      const SurfaceGeometry cap = hit_surface(c, Ray{o, d}, 1.0f);
      EXPECT_NEAR(cap.ng[axis], -sign, 1e-6f);
      // Across the axis: through the side.
      const int other = (axis + 1) % 3;
      Vec3f o2(-0.0f), d2(-0.0f);
      o2[axis] = 1.0f;
      o2[other] = -3.0f * sign;
      d2[other] = sign;
      const SurfaceGeometry side = hit_surface(c, Ray{o2, d2}, 2.0f);
      EXPECT_NEAR(side.ng[other], -sign, 1e-6f);
    }
  }
}

TEST(Cylinder, RimHasNoCrackBetweenSideAndCap) {
  const Cylinder c{{0.3f, -0.2f, 0.1f}, {1.1f, 0.9f, 2.3f}, 0.7f};
  const Vec3f axis = normalize(c.p1 - c.p0);
  Vec3f e0, e1;
  orthonormal_basis(axis, e0, e1);
  test::Rng rng(3);
  int misses = 0;
  for (int i = 0; i < 20000; ++i) {
    const bool top = i % 2 == 1;
    const float phi = rng.uniform(0.0f, 2.0f * kPi);
    const Vec3f radial = std::cos(phi) * e0 + std::sin(phi) * e1;
    const Vec3f rim = (top ? c.p1 : c.p0) + c.radius * radial;
    // From a point whose nearest point on the solid is this rim point (the
    // normal cone spanned by the cap normal and the radial direction).
    const float a = rng.uniform(0.0f, 1.0f);
    const Vec3f w = normalize(a * (top ? axis : -axis) + (1.0f - a) * radial);
    const Vec3f origin = rim + 3.0f * w;
    const Ray ray{origin, rim - origin};
    PrimHit hit;
    if (!intersect(c, ray, hit)) {
      ++misses;
    } else {
      // Rays grazing the side or the cap meet it where t is ill-conditioned;
      // the reprojected point is still on the surface, near the rim.
      EXPECT_NEAR(hit.t, 1.0f, 1e-3f);
      const Vec3f p = surface(c, ray, hit).p;
      EXPECT_LT(length(p - rim), 3e-3f);
      const float h = dot(p - c.p0, axis);
      const float dist_axis = length(p - c.p0 - h * axis);
      const float len = length(c.p1 - c.p0);
      const bool on_side = std::fabs(dist_axis - c.radius) < 1e-5f;
      const bool on_cap = std::fabs(h - (top ? len : 0.0f)) < 1e-5f && dist_axis < c.radius + 1e-5f;
      EXPECT_TRUE(on_side || on_cap);
    }
  }
  EXPECT_EQ(misses, 0);
}

TEST(Cylinder, DegenerateCylindersNeverHit) {
  PrimHit hit;
  const Ray ray{{0, 0, -5}, {0, 0, 1}};
  const Ray across{{-5, 0, 0.5f}, {1, 0, 0}};
  for (const Cylinder& c : {Cylinder{{0, 0, 0}, {0, 0, 1}, 0.0f}, Cylinder{{0, 0, 0}, {0, 0, 1}, -1.0f},
                            Cylinder{{0, 0, 0}, {0, 0, 0}, 1.0f}, Cylinder{{0, 0, 0}, {0, 0, 1}, kNaN},
                            Cylinder{{0, 0, kNaN}, {0, 0, 1}, 1.0f}}) {
    EXPECT_FALSE(intersect(c, ray, hit));
    EXPECT_FALSE(intersect(c, across, hit));
  }
}

TEST(Cylinder, NonFiniteRaysNeverHit) {
  PrimHit hit;
  EXPECT_FALSE(intersect(kZ, Ray{{kNaN, 0, 1}, {1, 0, 0}}, hit));
  EXPECT_FALSE(intersect(kZ, Ray{{-5, 0, 1}, {1, kNaN, 0}}, hit));
  EXPECT_FALSE(intersect(kZ, Ray{{-kInfinity, 0, 1}, {1, 0, 0}}, hit));
  EXPECT_FALSE(intersect(kZ, Ray{{-5, 0, 1}, {kInfinity, 0, 0}}, hit));
  EXPECT_FALSE(intersect(kZ, Ray{{-5, 0, 1}, {0, 0, 0}}, hit));
  EXPECT_FALSE(intersect(kZ, Ray{{0, 0, 1}, {0, 0, 0}}, hit));
  EXPECT_FALSE(intersect(kZ, Ray{{-5, 0, 1}, {1, 0, 0}, kNaN, kInfinity}, hit));
  EXPECT_FALSE(intersect(kZ, Ray{{-5, 0, 1}, {1, 0, 0}, 0.0f, kNaN}, hit));
}

TEST(Cylinder, IntervalIsOpenOnBothEnds) {
  PrimHit hit;
  const Ray base{{-5, 0, 1}, {1, 0, 0}};
  Ray r = base;
  r.tmax = 4.0f;
  EXPECT_FALSE(intersect(kZ, r, hit));
  r.tmax = std::nextafter(4.0f, 5.0f);
  ASSERT_TRUE(intersect(kZ, r, hit));
  EXPECT_FLOAT_EQ(hit.t, 4.0f);
  r = base;
  r.tmin = 4.0f;  // the entry is excluded: the exit is next
  ASSERT_TRUE(intersect(kZ, r, hit));
  EXPECT_FLOAT_EQ(hit.t, 6.0f);
  r.tmin = 6.0f;
  EXPECT_FALSE(intersect(kZ, r, hit));
}

TEST(Cylinder, SurfacePointLiesOnTheSurface) {
  const Cylinder c{{10, -20, 5}, {12, -17, 9}, 0.5f};
  const Vec3f axis = normalize(c.p1 - c.p0);
  const float len = length(c.p1 - c.p0);
  test::Rng rng(5);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3f target = c.p0 + rng.uniform() * (c.p1 - c.p0) + 0.6f * rng.unit_vector();
    const Vec3f origin = target + 20.0f * rng.unit_vector();
    const Ray ray{origin, normalize(target - origin)};
    PrimHit hit;
    if (!intersect(c, ray, hit)) continue;
    ++hits;
    const SurfaceGeometry sg = surface(c, ray, hit);
    const Vec3f q = sg.p - c.p0;
    const float h = dot(q, axis);
    const float radial = length(q - h * axis);
    const bool on_side = std::fabs(radial - c.radius) < 1e-5f && h > -1e-5f && h < len + 1e-5f;
    const bool on_cap = (std::fabs(h) < 1e-5f || std::fabs(h - len) < 1e-5f) && radial < c.radius + 1e-5f;
    EXPECT_TRUE(on_side || on_cap) << "h " << h << " radial " << radial;
    EXPECT_LT(dot(sg.ng, ray.dir), 1e-6f);  // from outside: the outward normal faces the ray
    EXPECT_GE(sg.uv.x, 0.0f);
    EXPECT_LT(sg.uv.x, 1.0f);
    EXPECT_GE(sg.uv.y, 0.0f);
    EXPECT_LE(sg.uv.y, 1.0f);
  }
  EXPECT_GT(hits, 500);
}

}  // namespace
}  // namespace pt

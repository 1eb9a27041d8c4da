#include <gtest/gtest.h>

#include <cmath>

#include "geometry/shapes.h"
#include "test_util.h"

namespace pt {
namespace {

const Cone kCone{{0, 0, 0}, {0, 0, 2}, 1.0f, 0.0f};       // pointed, apex at z = 2
const Cone kFrustum{{0, 0, 0}, {0, 0, 2}, 1.0f, 0.5f};    // truncated

using test::hit_surface;

TEST(Cone, SideHitHasSlantedNormalAndTextureCoordinates) {
  // At z = 1 the radius is 0.5; the outward normal is (2, 0, 1) / sqrt(5).
  const SurfaceGeometry sg = hit_surface(kCone, Ray{{5, 0, 1}, {-1, 0, 0}}, 4.5f);
  EXPECT_NEAR(sg.ng.x, 2.0f / std::sqrt(5.0f), 1e-6f);
  EXPECT_NEAR(sg.ng.z, 1.0f / std::sqrt(5.0f), 1e-6f);
  EXPECT_NEAR(sg.p.x, 0.5f, 1e-6f);
  EXPECT_NEAR(sg.uv.x, 0.0f, 1e-6f);
  EXPECT_NEAR(sg.uv.y, 0.5f, 1e-6f);
  const SurfaceGeometry sy = hit_surface(kFrustum, Ray{{0, 5, 1}, {0, -1, 0}}, 4.25f);
  EXPECT_NEAR(sy.uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(sy.uv.y, 0.5f, 1e-6f);
}

TEST(Cone, CapsAndApex) {
  const SurfaceGeometry base = hit_surface(kCone, Ray{{0.5f, 0.2f, -3}, {0, 0, 1}}, 3.0f);
  EXPECT_FLOAT_EQ(base.ng.z, -1.0f);
  EXPECT_FLOAT_EQ(base.uv.y, 0.0f);
  const SurfaceGeometry top = hit_surface(kFrustum, Ray{{0.3f, 0, 5}, {0, 0, -1}}, 3.0f);
  EXPECT_FLOAT_EQ(top.ng.z, 1.0f);
  EXPECT_FLOAT_EQ(top.uv.y, 1.0f);
  PrimHit hit;
  EXPECT_FALSE(intersect(kFrustum, Ray{{0.6f, 0, 5}, {0, 0, -1}}, hit) && hit.t < 3.1f);  // beside the top cap
  // Straight down the axis onto the apex: the side, at the apex.
  const SurfaceGeometry apex = hit_surface(kCone, Ray{{0, 0, 5}, {0, 0, -1}}, 3.0f);
  EXPECT_NEAR(apex.p.z, 2.0f, 1e-5f);
}

TEST(Cone, RaysFromInsideFindTheExit) {
  const SurfaceGeometry side = hit_surface(kCone, Ray{{0, 0, 1}, {1, 0, 0}}, 0.5f);
  EXPECT_GT(side.ng.x, 0.8f);
  const SurfaceGeometry down = hit_surface(kFrustum, Ray{{0.2f, 0, 1}, {0, 0, -1}}, 1.0f);
  EXPECT_FLOAT_EQ(down.ng.z, -1.0f);
}

TEST(Cone, MissesOutsideAndAboveTheApex) {
  PrimHit hit;
  EXPECT_FALSE(intersect(kCone, Ray{{5, 0, 2.5f}, {-1, 0, 0}}, hit));   // the other nappe's height
  EXPECT_FALSE(intersect(kCone, Ray{{5, 0, 1.8f}, {-1, 0, 0.0f}}, hit) && std::fabs(hit.t - 4.9f) > 1e-4f);
  ASSERT_TRUE(intersect(kCone, Ray{{0.9f, 0, 5}, {0, 0, -1}}, hit));  // the side where the radius is 0.9
  EXPECT_NEAR(hit.t, 4.8f, 1e-5f);
  EXPECT_FALSE(intersect(kCone, Ray{{5, 0, 1}, {1, 0, 0}}, hit));
  // Along a line of the upper (other) nappe: never part of the solid.
  EXPECT_FALSE(intersect(kCone, Ray{{-1, 0, 4}, {1, 0, -2}, 0.0f, 0.99f}, hit));
}

TEST(Cone, AreaSamplesLieOnTheSurfaceInProportionToArea) {
  const Cone tilted{{1, -2, 3}, {1.5f, 0, 2.2f}, 0.8f, 0.0f};
  test::expect_samples_hit_along_normal(tilted, 3000, 2e-4f);
  const Cone frustum{{1, -2, 3}, {1.5f, 0, 2.2f}, 0.8f, 0.3f};
  test::expect_samples_hit_along_normal(frustum, 3000, 2e-4f);
  const Cone flared{{1, -2, 3}, {1.5f, 0, 2.2f}, 0.3f, 0.9f};
  test::expect_samples_hit_along_normal(flared, 3000, 2e-4f);
  // A pointed cone of radius 1, height 2: side pi sqrt(5), base pi. The centroid
  // of the side is at h = 2/3, of the base at 0.
  const Vec3f mean = test::expect_samples_hit_along_normal(kCone, 20000, 2e-4f);
  const float side = kPi * std::sqrt(5.0f), base = kPi;
  EXPECT_NEAR(make_area_sampler(kCone).area, side + base, 1e-4f);
  EXPECT_NEAR(mean.z, side * (2.0f / 3.0f) / (side + base), 0.02f);
}

TEST(Cone, CheckNamesTheField) {
  ShapeChecker c;
  check(Cone{{0, 0, 0}, {0, 0, 1}, 0.0f, -1.0f}, c);
  ASSERT_EQ(c.problems().size(), 2u);
  EXPECT_EQ(c.problems()[0].field, "radius");
  EXPECT_EQ(c.problems()[1].field, "top_radius");
}

}  // namespace
}  // namespace pt

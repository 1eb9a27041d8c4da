#include <gtest/gtest.h>

#include <cmath>

#include "geometry/shapes.h"
#include "test_util.h"

namespace pt {
namespace {

TEST(InfinitePlane, HitToTheHorizonWithPlanarTextureCoordinates) {
  const InfinitePlane pl = make_plane({0, -1, 0}, {0, 2, 0}, {}, 2.0f);
  PrimHit hit;
  const Ray ray{{3, 4, 5}, {0, -1, 0}};
  ASSERT_TRUE(intersect(pl, 0, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 5.0f);
  const SurfaceGeometry sg = surface(pl, 0, ray, hit);
  EXPECT_FLOAT_EQ(sg.ng.y, 1.0f);
  // Tangent +x (fp::axis_frame of +y), bitangent y x x = -z; uv = distance / uv_scale.
  EXPECT_FLOAT_EQ(sg.uv.x, 1.5f);
  EXPECT_FLOAT_EQ(sg.uv.y, -2.5f);
  const Ray far{{0, 1, 0}, normalize(Vec3f(1, -1e-6f, 0))};
  ASSERT_TRUE(intersect(pl, 0, far, hit));
  EXPECT_NEAR(hit.t, 2e6f, 2.0f);
  EXPECT_NEAR(surface(pl, 0, far, hit).p.y, -1.0f, 1e-6f);
  EXPECT_FALSE(intersect(pl, 0, Ray{{0, 0, 0}, {1, 0, 0}}, hit));   // parallel
  EXPECT_FALSE(intersect(pl, 0, Ray{{0, 0, 0}, {0, 1, 0}}, hit));   // away
  EXPECT_TRUE(bounds(pl).empty());
  EXPECT_EQ(primitive_count(pl), 0u);
}

TEST(InfinitePlane, TangentSetsTheTextureOrientation) {
  const InfinitePlane pl = make_plane({0, 0, 0}, {0, 0, 1}, {1, 1, 0.5f}, 1.0f);
  EXPECT_NEAR(dot(pl.tangent, pl.normal), 0.0f, 1e-6f);
  EXPECT_NEAR(pl.tangent.x, std::sqrt(0.5f), 1e-6f);
  const Ray ray{{1, 1, 1}, {0, 0, -1}};
  PrimHit hit;
  ASSERT_TRUE(intersect(pl, 0, ray, hit));
  const SurfaceGeometry sg = surface(pl, 0, ray, hit);
  EXPECT_NEAR(sg.uv.x, std::sqrt(2.0f), 1e-6f);
  EXPECT_NEAR(sg.uv.y, 0.0f, 1e-6f);
}

TEST(InfinitePlane, CheckNamesTheField) {
  ShapeChecker c;
  check(make_plane({0, 0, 0}, {0, 1, 0}, {0, 3, 0}, 0.0f), c);
  ASSERT_EQ(c.problems().size(), 2u);
  EXPECT_EQ(c.problems()[0].field, "tangent");
  EXPECT_EQ(c.problems()[1].field, "uv_scale");
  ShapeChecker z;
  check(make_plane({0, 0, 0}, {0, 0, 0}, {}, 1.0f), z);
  EXPECT_FALSE(z.usable());
}

}  // namespace
}  // namespace pt

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/shapes.h"
#include "test_util.h"

namespace pt {
namespace {

const Disc kDisc = make_disc({0, 0, 1}, {0, 0, 2}, 2.0f, 0.0f);
const Disc kAnnulus = make_disc({0, 0, 1}, {0, 0, 1}, 2.0f, 1.0f);

TEST(Disc, HitHasNormalAndPbrtTextureCoordinates) {
  PrimHit hit;
  const Ray ray{{1, 0, 5}, {0, 0, -1}};
  ASSERT_TRUE(intersect(kDisc, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 4.0f);
  const SurfaceGeometry sg = surface(kDisc, ray, hit);
  EXPECT_FLOAT_EQ(sg.ng.z, 1.0f);
  EXPECT_FLOAT_EQ(sg.p.z, 1.0f);
  EXPECT_NEAR(sg.uv.x, 0.0f, 1e-6f);  // phi from +x (fp::axis_frame of +z)
  EXPECT_NEAR(sg.uv.y, 0.5f, 1e-6f);  // (radius - r) / radius
  const Ray up{{0, 1.5f, -3}, {0, 0, 2}};  // from behind: the same normal (not flipped)
  ASSERT_TRUE(intersect(kDisc, up, hit));
  const SurfaceGeometry sb = surface(kDisc, up, hit);
  EXPECT_FLOAT_EQ(sb.ng.z, 1.0f);
  EXPECT_NEAR(sb.uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(sb.uv.y, 0.25f, 1e-6f);
}

TEST(Disc, AnnulusHasAHoleAndVFromRimToInnerRim) {
  PrimHit hit;
  EXPECT_FALSE(intersect(kAnnulus, Ray{{0.5f, 0.5f, 5}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect(kAnnulus, Ray{{2.01f, 0, 5}, {0, 0, -1}}, hit));
  const Ray ray{{-1.5f, 0, 5}, {0, 0, -1}};
  ASSERT_TRUE(intersect(kAnnulus, ray, hit));
  const SurfaceGeometry sg = surface(kAnnulus, ray, hit);
  EXPECT_NEAR(sg.uv.x, 0.5f, 1e-6f);
  EXPECT_NEAR(sg.uv.y, 0.5f, 1e-6f);
}

TEST(Disc, MissesParallelNonFiniteAndOutOfInterval) {
  PrimHit hit;
  EXPECT_FALSE(intersect(kDisc, Ray{{0, 0, 1}, {1, 0, 0}}, hit));  // in its plane
  EXPECT_FALSE(intersect(kDisc, Ray{{0, 0, 5}, {0, 0, 1}}, hit));  // away
  EXPECT_FALSE(intersect(kDisc, Ray{{0, 0, 5}, {0, 0, -1}, 0.0f, 4.0f}, hit));  // open interval
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(intersect(kDisc, Ray{{nan, 0, 5}, {0, 0, -1}}, hit));
  EXPECT_FALSE(intersect(make_disc({0, 0, 0}, {0, 0, 1}, 0.0f, 0.0f), Ray{{0, 0, 5}, {0, 0, -1}}, hit));
}

TEST(Disc, BoundsAreTightForATiltedDisc) {
  const Bounds3f b = bounds(kDisc);
  EXPECT_NEAR(b.hi.x, 2.0f, 1e-5f);
  EXPECT_NEAR(b.hi.z, 1.0f, 1e-5f);
}

TEST(Disc, AreaSamplesLieOnTheDiscAndAreCentred) {
  const Disc tilted = make_disc({1, -2, 3}, {0.3f, 1, -0.4f}, 1.5f, 0.0f);
  EXPECT_LT(length(test::expect_samples_hit_along_normal(tilted) - tilted.center), 0.05f);
  const Disc annulus = make_disc({1, -2, 3}, {0.3f, 1, -0.4f}, 1.5f, 0.7f);
  test::expect_samples_hit_along_normal(annulus);
  EXPECT_NEAR(make_area_sampler(annulus).area, kPi * (1.5f * 1.5f - 0.7f * 0.7f), 1e-4f);
}

TEST(Disc, CheckNamesTheField) {
  ShapeChecker c;
  check(make_disc({0, 0, 0}, {0, 0, 1}, 1.0f, 1.0f), c);
  ASSERT_EQ(c.problems().size(), 1u);
  EXPECT_EQ(c.problems()[0].field, "inner_radius");
  ShapeChecker z;
  check(make_disc({0, 0, 0}, {0, 0, 0}, -1.0f, 0.0f), z);
  ASSERT_EQ(z.problems().size(), 2u);
  EXPECT_EQ(z.problems()[0].field, "radius");
  EXPECT_EQ(z.problems()[1].field, "normal");
}

}  // namespace
}  // namespace pt

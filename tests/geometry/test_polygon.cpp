#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/shapes.h"
#include "test_util.h"

namespace pt {
namespace {

std::vector<Vec3f> regular(int n, float r, float z) {
  std::vector<Vec3f> v;
  for (int k = 0; k < n; ++k) {
    const float phi = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(n);
    v.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  return v;
}

std::vector<ShapeProblem> problems(const std::vector<Vec3f>& v) {
  ShapeChecker c;
  check(make_polygon(v), c);
  return c.problems();
}

TEST(Polygon, HexagonIsHitInsideAndMissedOutside) {
  const ConvexPolygon hex = make_polygon(regular(6, 1.0f, 2.0f));
  PrimHit hit;
  const Ray ray{{0.3f, -0.4f, 5}, {0, 0, -1}};
  ASSERT_TRUE(intersect(hex, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 3.0f);
  const SurfaceGeometry sg = surface(hex, ray, hit);
  EXPECT_FLOAT_EQ(sg.ng.z, 1.0f);
  EXPECT_FLOAT_EQ(sg.p.z, 2.0f);
  EXPECT_FALSE(intersect(hex, Ray{{0.95f, 0.5f, 5}, {0, 0, -1}}, hit));  // beyond an edge
}

TEST(Polygon, RectangleHasTheQuadsTextureCoordinates) {
  const std::vector<Vec3f> v = {{0, 0, 0}, {4, 0, 0}, {4, 0, 2}, {0, 0, 2}};
  const ConvexPolygon p = make_polygon(v);
  const Quad q{{v[0], v[1], v[2], v[3]}};
  for (const Vec3f o : {Vec3f(1, 3, 0.5f), Vec3f(3.5f, 3, 1.9f), Vec3f(0.1f, 3, 1.2f)}) {
    const Ray ray{o, {0, -1, 0}};
    PrimHit hp, hq;
    ASSERT_TRUE(intersect(p, ray, hp));
    ASSERT_TRUE(intersect(q, ray, hq));
    const SurfaceGeometry sp = surface(p, ray, hp), sq = surface(q, ray, hq);
    EXPECT_NEAR(sp.uv.x, sq.uv.x, 1e-6f);
    EXPECT_NEAR(sp.uv.y, sq.uv.y, 1e-6f);
    EXPECT_FLOAT_EQ(sp.ng.y, sq.ng.y);
  }
}

TEST(Polygon, HexagonMapsItsBoundingRectangleInTheFirstEdgesFrame) {
  // docs/geometry.md: eu = the first edge v0 -> v1, ev = normal x eu, the
  // bounding rectangle in that frame onto [0, 1]^2. For the regular hexagon
  // of radius 1 (normal +z) the rectangle is 2 long along eu (corners 5 and 2)
  // and sqrt(3) across (edges 0-1 and 3-4), centred on the centre.
  const std::vector<Vec3f> v = regular(6, 1.0f, 2.0f);
  const ConvexPolygon hex = make_polygon(v);
  const Vec3f eu = normalize(v[1] - v[0]);
  const Vec3f ev = cross(Vec3f(0, 0, 1), eu);
  const float across = std::sqrt(3.0f);
  for (const float a : {-0.9f, -0.3f, 0.0f, 0.4f, 0.8f}) {
    for (const float b : {-0.7f, 0.0f, 0.2f, 0.6f}) {
      const Vec3f p = a * eu + b * ev;
      if (std::abs(b) > across / 2 * 0.99f || std::abs(a) + std::abs(b) / across > 0.99f) continue;  // outside
      const Ray ray{{p.x, p.y, 5}, {0, 0, -1}};
      PrimHit hit;
      ASSERT_TRUE(intersect(hex, ray, hit)) << a << " " << b;
      const SurfaceGeometry sg = surface(hex, ray, hit);
      EXPECT_NEAR(sg.uv.x, 0.5f + a / 2, 1e-5f) << a << " " << b;
      EXPECT_NEAR(sg.uv.y, 0.5f + b / across, 1e-5f) << a << " " << b;
    }
  }
}

TEST(Polygon, AreaSamplesLieOnThePolygon) {
  std::vector<Vec3f> v = regular(7, 1.3f, 0.0f);
  for (Vec3f& p : v) p = Vec3f(p.x + 0.4f * p.z, p.y, p.x * 0.5f + 2.0f);  // tilted, still planar
  const ConvexPolygon p = make_polygon(v);
  const Vec3f mean = test::expect_samples_hit_along_normal(p);
  EXPECT_LT(length(mean - Vec3f(0, 0, 2)), 0.05f);
  EXPECT_NEAR(make_area_sampler(p).area, 0.5f * 7 * 1.3f * 1.3f * std::sin(2 * kPi / 7) * std::sqrt(1.25f), 1e-3f);
}

TEST(Polygon, NonPlanarCornerIsNamed) {
  std::vector<Vec3f> v = regular(5, 1.0f, 0.0f);
  v[3].z = 0.05f;
  const auto ps = problems(v);
  ASSERT_EQ(ps.size(), 1u);
  EXPECT_EQ(ps[0].field, "vertices[3]");
  EXPECT_NE(ps[0].message.find("not planar"), std::string::npos);
  v[3].z = 0.0005f;  // within 1e-3 of the size
  EXPECT_TRUE(problems(v).empty());
}

TEST(Polygon, ReflexCornerIsNamed) {
  // An arrow: corner 3 points inwards.
  const auto ps = problems({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, 0.8f, 0}, {0, 2, 0}});
  ASSERT_EQ(ps.size(), 1u);
  EXPECT_EQ(ps[0].field, "vertices[3]");
  EXPECT_NE(ps[0].message.find("not convex"), std::string::npos);
}

TEST(Polygon, StarIsRefused) {
  const std::vector<Vec3f> five = regular(5, 1.0f, 0.0f);
  const auto ps = problems({five[0], five[2], five[4], five[1], five[3]});
  ASSERT_EQ(ps.size(), 1u);
  EXPECT_EQ(ps[0].field, "vertices");
}

TEST(Polygon, TooFewCornersAreUnusableAndZeroAreaWarns) {
  ShapeChecker c;
  check(make_polygon({{0, 0, 0}, {1, 0, 0}}), c);
  EXPECT_FALSE(c.usable());
  const auto ps = problems({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
  ASSERT_EQ(ps.size(), 1u);
  EXPECT_TRUE(ps[0].warning);
}

}  // namespace
}  // namespace pt

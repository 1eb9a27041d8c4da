// core/transform.h: composition order, inverse, normals (inverse transpose),
// similarity detection, and the error bound of transformed points.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/transform.h"

namespace pt {
namespace {

void expect_near(Vec3f a, Vec3f b, float eps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

TEST(Transform, StepsComposeFirstAppliedFirst) {
  // scale, then rotate 90 degrees about z, then translate: (1, 0, 0) -> (2, 0, 0) -> (0, 2, 0) -> (0, 2, 5).
  const Affine a = Affine::translate(0, 0, 5) * Affine::rotate(0, 0, 1, 90) * Affine::scale(2, 2, 2);
  const Transform t(a);
  expect_near(t.point({1, 0, 0}), {0, 2, 5}, 1e-6f);
  expect_near(t.vector({1, 0, 0}), {0, 2, 0}, 1e-6f);
  expect_near(t.inverse_point({0, 2, 5}), {1, 0, 0}, 1e-6f);
  EXPECT_TRUE(t.similarity);
  EXPECT_NEAR(t.scale, 2.0f, 1e-6f);
  EXPECT_NEAR(t.det, 8.0f, 1e-5f);
  EXPECT_FALSE(t.is_identity());
  EXPECT_TRUE(Transform().is_identity());
}

TEST(Transform, RotationIsCounterClockwiseAboutTheAxis) {
  const Transform t(Affine::rotate(0, 1, 0, 90));  // about +y: +z goes to +x
  expect_near(t.point({0, 0, 1}), {1, 0, 0}, 1e-6f);
}

TEST(Transform, NormalsStayPerpendicularAndOutwardUnderAnyAffineMap) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int k = 0; k < 200; ++k) {
    Affine a;
    for (auto& row : a.m) {
      for (double& v : row) v = u(rng);
    }
    if (!a.invertible()) continue;
    const Transform t(a);
    const Vec3f n = normalize(Vec3f(float(u(rng)), float(u(rng)), float(u(rng))));
    Vec3f e1, e2;
    orthonormal_basis(n, e1, e2);
    const Vec3f nw = normalize(t.normal(n));
    EXPECT_NEAR(dot(nw, normalize(t.vector(e1))), 0.0f, 1e-4f);
    EXPECT_NEAR(dot(nw, normalize(t.vector(e2))), 0.0f, 1e-4f);
    // Outward: the point one step along n maps to the normal's side, mirrored or not.
    EXPECT_GT(dot(t.vector(n), nw), 0.0f);
  }
}

TEST(Transform, MirrorHasNegativeDeterminantAndIsASimilarity) {
  const Transform t(Affine::scale(-1, 1, 1));
  EXPECT_LT(t.det, 0.0f);
  EXPECT_TRUE(t.similarity);
  expect_near(normalize(t.normal({1, 0, 0})), {-1, 0, 0}, 0.0f);
  EXPECT_FALSE(Transform(Affine::scale(1, 2, 1)).similarity);
}

TEST(Transform, SingularAndNonFiniteMapsAreNotInvertible) {
  EXPECT_FALSE(Affine::scale(1, 0, 1).invertible());
  Affine a;
  a.m[1][3] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(a.invertible());
  Affine flat;  // two equal rows
  flat.m[1][0] = 1;
  flat.m[1][1] = 0;
  EXPECT_FALSE(flat.invertible());
  EXPECT_TRUE(Affine::scale(1e-4, 1e-4, 1e-4).invertible());
  EXPECT_TRUE(Affine::scale(1e4, 1e-4, 1).invertible());
}

TEST(Transform, PointErrorBoundsTheRoundingOfTransformedPoints) {
  // Compared with the same map in double: the float result is within the bound.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 2000; ++k) {
    const double s = std::pow(10.0, 4 * u(rng));
    const Affine a = Affine::translate(1e4 * u(rng), 1e3 * u(rng), u(rng)) *
                     Affine::rotate(u(rng), u(rng), u(rng) + 2, 180 * u(rng)) * Affine::scale(s, s * 0.5, s);
    const Transform t(a);
    const Vec3f p(float(100 * u(rng)), float(u(rng)), float(1e-3 * u(rng)));
    const Vec3f q = t.point(p);
    const Vec3f e = t.point_error(p, Vec3f(0.0f));
    for (int i = 0; i < 3; ++i) {
      // The exact image of p under the float matrix (double products and sums are exact enough).
      const double exact = double(t.m[i][0]) * p.x + double(t.m[i][1]) * p.y + double(t.m[i][2]) * p.z + t.m[i][3];
      EXPECT_LE(std::fabs(double(q[i]) - exact), double(e[i])) << k;
    }
  }
}

TEST(Transform, BoundsHoldEveryTransformedCorner) {
  const Transform t(Affine::rotate(1, 1, 1, 33) * Affine::scale(3, 0.2f, 1));
  Bounds3f b;
  b.extend(Vec3f(-1, -2, -3));
  b.extend(Vec3f(4, 5, 6));
  const Bounds3f w = t.bounds(b);
  for (int c = 0; c < 8; ++c) {
    const Vec3f p = t.point({(c & 1) ? 4.0f : -1.0f, (c & 2) ? 5.0f : -2.0f, (c & 4) ? 6.0f : -3.0f});
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(w.lo[a], p[a]);
      EXPECT_GE(w.hi[a], p[a]);
    }
  }
}

}  // namespace
}  // namespace pt

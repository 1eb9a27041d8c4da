// Every shape's uv_derivatives (the tangent frame of normal and bump maps)
// against finite differences of its own surface(): for two nearby points found
// by rays, p2 - p1 = dp/du (u2 - u1) + dp/dv (v2 - v1) to first order.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/rng.h"
#include "geometry/shapes.h"

namespace pt {
namespace {

// The point of `s` the ray from `q + n` towards `q` finds.
bool hit_near(const Shape& s, Vec3f q, Vec3f n, SurfaceGeometry& sg) {
  const Ray ray{q + n * 0.5f, -n, 0.0f, kInfinity};
  return std::visit(
      [&](const auto& shape) {
        PrimHit hit;
        if (!intersect_primitive(shape, 0, ray, hit)) return false;
        sg = surface_of_primitive(shape, 0, ray, hit);
        return true;
      },
      s);
}

void check_shape(const Shape& s, const char* name) {
  const ShapeAreaSampler sampler = make_area_sampler(s);
  Rng rng(9);
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    Vec3f q, n;
    std::visit([&](const auto& a) { a.sample(Vec2f(rng.next_float(), rng.next_float()), q, n); }, sampler);
    SurfaceGeometry a, b;
    if (!hit_near(s, q, n, a)) continue;
    Vec3f t1, t2;
    orthonormal_basis(a.ng, t1, t2);
    const Vec3f step = (t1 * (rng.next_float() - 0.5f) + t2 * (rng.next_float() - 0.5f)) * 2e-3f;
    if (!hit_near(s, a.p + step, a.ng, b)) continue;
    const Vec2f duv = b.uv - a.uv;
    if (std::fabs(duv.x) > 0.1f || std::fabs(duv.y) > 0.1f) continue;  // across a seam
    if (std::fabs(dot(a.ng, b.ng)) < 0.999f) continue;                 // across an edge (side to cap)
    const UvDerivatives d = uv_derivatives(s, 0, a);
    Vec3f predicted = d.dpdu * duv.x + d.dpdv * duv.y;
    Vec3f actual = b.p - a.p;
    if (d.dpdv == Vec3f(0.0f)) {
      // A cap: v is constant and uv do not determine the point; only the
      // component along dp/du (the circle through it) is predicted.
      const Vec3f along = normalize(d.dpdu);
      predicted = along * dot(predicted, along);
      actual = along * dot(actual, along);
    }
    EXPECT_LT(length(predicted - actual), 0.02f * length(b.p - a.p) + 1e-6f)
        << name << " at " << a.p.x << "," << a.p.y << "," << a.p.z << " uv " << a.uv.x << "," << a.uv.y;
    ++checked;
  }
  EXPECT_GT(checked, 100) << name;
}

TEST(UvDerivatives, MatchFiniteDifferencesOfEveryShape) {
  check_shape(Sphere{Vec3f(0.5f, -1.0f, 2.0f), 1.5f, normalize(Vec3f(0.3f, 1.0f, 0.2f))}, "sphere");
  check_shape(Cylinder{Vec3f(0, 0, 0), Vec3f(0.5f, 2.0f, 0.3f), 0.7f}, "cylinder");
  check_shape(Cone{Vec3f(0, 0, 0), Vec3f(0.2f, 1.5f, -0.3f), 0.9f, 0.3f}, "cone");
  check_shape(make_disc(Vec3f(1, 2, 3), normalize(Vec3f(0.2f, 0.4f, 1.0f)), 1.3f, 0.4f), "disc");
  check_shape(make_polygon({Vec3f(0, 0, 0), Vec3f(2, 0, 0.2f), Vec3f(2.5f, 1.5f, 0.325f), Vec3f(0.5f, 2, 0.15f)}),
              "polygon");
  check_shape(Quad{{Vec3f(0, 0, 0), Vec3f(2, 0, 0), Vec3f(2.6f, 1.5f, 0), Vec3f(-0.3f, 1.8f, 0)}}, "quad");
  TriangleMesh mesh = make_triangle(Vec3f(0, 0, 0), Vec3f(2, 0.3f, 0.1f), Vec3f(0.4f, 1.7f, -0.2f));
  check_shape(mesh, "triangle without uvs");
  mesh.uvs = {Vec2f(0.1f, 0.9f), Vec2f(0.8f, 0.7f), Vec2f(0.3f, 0.05f)};
  check_shape(mesh, "triangle with uvs");
}

TEST(UvDerivatives, PlaneFollowsItsTangentAndScale) {
  const InfinitePlane pl = make_plane(Vec3f(1, 0, 0), Vec3f(0, 1, 0), Vec3f(1, 0, 0), 2.0f);
  const UvDerivatives d = uv_derivatives(Shape(pl), 0, SurfaceGeometry{});
  EXPECT_EQ(d.dpdu, Vec3f(2, 0, 0));
  EXPECT_EQ(d.dpdv, cross(Vec3f(0, 1, 0), Vec3f(1, 0, 0)) * 2.0f);
}

}  // namespace
}  // namespace pt

// The shadow-terminator offset (geometry/terminator.h): Hanika's offset of a
// point of a smooth-shaded triangle to the surface its vertex normals imply,
// Cycles' rule for how much of it a direction gets, and the origins spawn_ray
// gives on a smooth mesh (self-intersection still holds).
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/shapes.h"
#include "geometry/terminator.h"
#include "test_util.h"

namespace pt {
namespace {

// Barycentric weights (w0, w1, w2) of a random point of a triangle.
Vec3f random_weights(test::Rng& rng) {
  float b1 = rng.uniform(), b2 = rng.uniform();
  if (b1 + b2 > 1.0f) {
    b1 = 1.0f - b1;
    b2 = 1.0f - b2;
  }
  return {1.0f - b1 - b2, b1, b2};
}

Vec3f at(const Vec3f v[3], Vec3f w) { return v[0] * w.x + v[1] * w.y + v[2] * w.z; }

// The side of the plane through v with normal n that p is on, in double.
double side(Vec3f p, Vec3f v, Vec3f n) {
  return (double(p.x) - v.x) * n.x + (double(p.y) - v.y) * n.y + (double(p.z) - v.z) * n.z;
}

TEST(Terminator, FlatTriangleWithEqualNormalsIsUnchanged) {
  test::Rng rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const float scale = std::pow(10.0f, rng.uniform(-3.0f, 3.0f));
    const Vec3f shift = rng.unit_vector() * (scale * rng.uniform(0.0f, 100.0f));
    const Vec3f v[3] = {shift + rng.unit_vector() * scale, shift + rng.unit_vector() * scale,
                        shift + rng.unit_vector() * scale};
    const Vec3f face = cross(v[1] - v[0], v[2] - v[0]);
    if (length(face) < 1e-3f * scale * scale) continue;
    const Vec3f n = normalize(face);
    const Vec3f normals[3] = {n, n, n};
    const Vec3f w = random_weights(rng);
    const Vec3f o = terminator_offset(at(v, w), v, normals, w);
    // Zero but for the rounding of the point's distance to the planes.
    EXPECT_LE(length(o), 1e-5f * (scale + length(shift))) << trial;
  }
}

// A triangle of a sphere's tessellation with the sphere's normals: the offset
// points out of the triangle's plane, towards the sphere (the surface the
// normals imply), and is zero at the corners.
TEST(Terminator, OffsetIsAlongTheBulgeOfAConvexTriangle) {
  test::Rng rng(11);
  const float r = 2.0f;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3f c = rng.unit_vector();
    // Corners 10-30 degrees apart around c.
    const float spread = rng.uniform(0.17f, 0.5f);
    Vec3f n[3], v[3];
    const Vec3f t = normalize(cross(c, std::fabs(c.x) < 0.9f ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0)));
    const Vec3f s = cross(c, t);
    for (int i = 0; i < 3; ++i) {
      const float a = 2.0f * kPi * static_cast<float>(i) / 3.0f;
      n[i] = normalize(c + spread * (t * std::cos(a) + s * std::sin(a)));
      v[i] = n[i] * r;
    }
    const Vec3f face = normalize(cross(v[1] - v[0], v[2] - v[0]));
    ASSERT_GT(dot(face, c), 0.0f);
    const Vec3f w = random_weights(rng);
    const Vec3f p = at(v, w);
    const Vec3f o = terminator_offset(p, v, n, w);
    EXPECT_GT(dot(o, face), 0.0f) << trial;
    // Outwards, nearly along the sphere's normal at p, by about twice the
    // point's depth under the sphere: the projections onto the corners'
    // tangent planes, weighted by the barycentrics, are Phong tessellation
    // with shape factor 1, which overshoots a sphere by about its sagitta
    // (harmless here: the origin ends above the smooth surface, not below).
    // Measured over 20,000 such points: 1.70-1.97 times the depth, cosine to
    // the radial direction at least 0.93.
    const float depth = r - length(p);
    if (depth < 1e-4f * r) continue;  // at a corner or along an edge's end
    EXPECT_GE(length(o), 1.5f * depth) << trial;
    EXPECT_LE(length(o), 2.1f * depth) << trial;
    EXPECT_GT(dot(normalize(o), normalize(p)), 0.9f) << trial;
    for (int i = 0; i < 3; ++i) {
      Vec3f corner(0.0f);
      (i == 0 ? corner.x : i == 1 ? corner.y : corner.z) = 1.0f;
      EXPECT_LE(length(terminator_offset(v[i], v, n, corner)), 1e-5f * r);
    }
  }
}

// Normals tilted inwards (a concave triangle): the triangle is above every
// tangent plane, nothing moves.
TEST(Terminator, ConcaveTriangleIsUnchanged) {
  const Vec3f v[3] = {{1, 0, 0}, {0, 1, 0}, {-1, -1, 0}};
  Vec3f n[3];
  for (int i = 0; i < 3; ++i) n[i] = normalize(Vec3f(0, 0, 1) - 0.4f * v[i]);  // leaning inwards: a bowl
  for (Vec3f w : {Vec3f(1, 1, 1) / 3.0f, Vec3f(0.6f, 0.3f, 0.1f), Vec3f(0.1f, 0.1f, 0.8f)})
    EXPECT_EQ(terminator_offset(at(v, w), v, n, w), Vec3f(0.0f));
}

TEST(Terminator, AmountFollowsCyclesRule) {
  const float c = 0.1f;
  EXPECT_EQ(terminator_amount(0.5f, 0.3f, 0.0f), 0.0f);   // off
  EXPECT_EQ(terminator_amount(0.05f, -0.1f, c), 1.0f);    // the triangle faces away
  EXPECT_EQ(terminator_amount(0.6f, -0.01f, c), 1.0f);
  EXPECT_EQ(terminator_amount(0.6f, 0.0f, c), 1.0f);
  EXPECT_EQ(terminator_amount(0.6f, 0.1f, c), 0.0f);      // faces it by the cutoff
  EXPECT_NEAR(terminator_amount(0.6f, 0.05f, c), 0.5f, 1e-6f);
  EXPECT_NEAR(terminator_amount(0.05f, 0.1f, c), 0.5f, 1e-6f);  // grazing shading normal: up to 2 cutoffs
  EXPECT_EQ(terminator_amount(0.05f, 0.2f, c), 0.0f);
  // Continuous where the two branches meet (cos_ns = cutoff).
  for (float g : {0.0f, 0.03f, 0.07f, 0.1f})
    EXPECT_NEAR(terminator_amount(c - 1e-6f, g, c), terminator_amount(c, g, c), 1e-4f);
}

// A coarse smooth-shaded sphere mesh: from every point, the origin of a ray
// leaving on the shading normal's side is on the outer side of its triangle,
// off it by the offset where the direction grazes, and a ray leaving above
// the triangle never meets the triangle again; rays into the sphere start on
// the inner side and reach the far side.
TEST(Terminator, SpawnedRaysOnASmoothMeshKeepTheSelfIntersectionPolicy) {
  for (float scale : {1e-3f, 1.0f, 1e3f}) {
    TriangleMesh m = test::make_uv_sphere(Vec3f(0.3f, -0.2f, 0.1f) * scale * 10.0f, scale, 6, 8);
    const Vec3f centre = Vec3f(0.3f, -0.2f, 0.1f) * scale * 10.0f;
    for (const Vec3f& p : m.positions) m.normals.push_back(normalize(p - centre));
    test::Rng rng(3);
    int offset_used = 0;
    for (uint32_t tri = 0; tri < m.triangle_count(); ++tri) {
      for (int k = 0; k < 20; ++k) {
        const Vec3f w = random_weights(rng);
        PrimHit hit;
        hit.uv = {w.y, w.z};
        hit.t = 1.0f;
        SurfaceGeometry sg = surface(m, tri, Ray{}, hit);
        sg.smooth = SmoothSurface{&m, nullptr, tri, hit.uv, 0.1f};
        const Vec3f dir = rng.hemisphere(sg.ns, 0.0f);
        const Ray ray = spawn_ray(sg, dir);
        const Vec3f v0 = m.positions[m.indices[3 * tri]];
        EXPECT_GT(side(ray.origin, v0, sg.ng), 0.0) << "starts under its triangle, scale " << scale;
        if (length(ray.origin - sg.p) > 1e-3f * scale) ++offset_used;
        PrimHit again;
        if (dot(dir, sg.ng) > 0.0f) {
          EXPECT_FALSE(intersect(m, tri, ray, again)) << "re-hit, scale " << scale;
        }
        // Into the sphere: from under the triangle, never meeting it.
        const Ray in = spawn_ray(sg, -sg.ns);
        EXPECT_LT(side(in.origin, v0, sg.ng), 0.0);
        EXPECT_FALSE(intersect(m, tri, in, again));
      }
    }
    EXPECT_GT(offset_used, 20) << "the offset never applied";
  }
}

}  // namespace
}  // namespace pt

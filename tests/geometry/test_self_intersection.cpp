// The self-intersection policy: rays spawned from surface points never re-hit
// the surface they leave (at any scale, far from the origin, on both sides),
// contact shadows survive, and closed surfaces do not leak at shared edges.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "geometry/shapes.h"
#include "test_util.h"

namespace pt {
namespace {

struct Placement {
  float scale;
  Vec3f offset;
  std::string name() const {
    return "scale " + std::to_string(scale) + " at (" + std::to_string(offset.x) + ", " +
           std::to_string(offset.y) + ", " + std::to_string(offset.z) + ")";
  }
};

std::vector<Placement> placements() {
  std::vector<Placement> out;
  for (float s : {1e-3f, 1e-1f, 1.0f, 1e2f, 1e4f}) {
    out.push_back({s, {0, 0, 0}});
    out.push_back({s, s * Vec3f(1000.0f, -700.0f, 300.0f)});  // far from the origin
    out.push_back({s, s * Vec3f(-30.0f, 20.0f, 10.0f)});
  }
  return out;
}

// Nearest hit over every triangle of a mesh (test-only brute force).
bool mesh_hit(const TriangleMesh& m, const Ray& ray, PrimHit& hit, uint32_t& prim) {
  Ray r = ray;
  bool found = false;
  for (uint32_t i = 0; i < m.triangle_count(); ++i) {
    PrimHit h;
    if (intersect(m, i, r, h)) {
      hit = h;
      prim = i;
      r.tmax = h.t;
      found = true;
    }
  }
  return found;
}

// A ray from outside aimed at a random point near `centre`.
Ray probe(test::Rng& rng, Vec3f centre, float scale, float spread) {
  const Vec3f target = centre + spread * scale * rng.uniform() * rng.unit_vector();
  const Vec3f origin = target + 5.0f * scale * rng.unit_vector();
  return Ray{origin, normalize(target - origin)};
}

constexpr int kPoints = 150;
constexpr int kDirections = 6;
constexpr float kMinCos = 1e-3f;

TEST(SelfIntersection, SpheresAtEveryScale) {
  test::Rng rng(21);
  for (const Placement& pl : placements()) {
    const Sphere s{pl.offset + pl.scale * Vec3f(0.1f, 0.2f, -0.3f), pl.scale, {0, 0, 1}};
    int rehits = 0, leaks = 0, samples = 0;
    for (int i = 0; i < kPoints; ++i) {
      const Ray cam = probe(rng, s.center, pl.scale, 0.9f);
      PrimHit hit;
      if (!intersect(s, cam, hit)) continue;
      const SurfaceGeometry sg = surface(s, cam, hit);
      for (int k = 0; k < kDirections; ++k) {
        ++samples;
        const Vec3f w = rng.hemisphere(sg.ng, kMinCos);
        PrimHit h;
        if (intersect(s, spawn_ray(sg, w), h)) ++rehits;  // convex: leaving outwards never hits
        if (!intersect(s, spawn_ray(sg, -w), h)) {
          ++leaks;  // entering: must reach the far side
        } else if (h.t < 0.5f * 2.0f * s.radius * dot(w, sg.ng)) {
          ++rehits;  // the chord is 2 r cos(theta)
        }
        const Vec3f light = sg.p + 3.0f * pl.scale * w;
        if (intersect(s, spawn_ray_to(sg, light), h)) ++rehits;
      }
    }
    EXPECT_GT(samples, kPoints * kDirections / 2) << pl.name();
    EXPECT_EQ(rehits, 0) << pl.name();
    EXPECT_EQ(leaks, 0) << pl.name();
  }
}

// Planar shapes are double-sided: rays leaving either side never re-hit.
template <class HitFn, class SurfaceFn>
void check_planar(test::Rng& rng, const Placement& pl, Vec3f centre, HitFn&& hit_fn, SurfaceFn&& surface_fn) {
  int rehits = 0, samples = 0;
  for (int i = 0; i < kPoints; ++i) {
    const Ray cam = probe(rng, centre, pl.scale, 0.5f);
    PrimHit hit;
    if (!hit_fn(cam, hit)) continue;
    const SurfaceGeometry sg = surface_fn(cam, hit);
    for (int k = 0; k < kDirections; ++k) {
      ++samples;
      const Vec3f w = rng.hemisphere(sg.ng, kMinCos);
      PrimHit h;
      if (hit_fn(spawn_ray(sg, w), h)) ++rehits;
      if (hit_fn(spawn_ray(sg, -w), h)) ++rehits;
      if (hit_fn(spawn_ray_to(sg, sg.p - 2.0f * pl.scale * w), h)) ++rehits;
    }
  }
  EXPECT_GT(samples, kPoints * kDirections / 4) << pl.name();
  EXPECT_EQ(rehits, 0) << pl.name();
}

TEST(SelfIntersection, QuadsAtEveryScale) {
  test::Rng rng(22);
  for (const Placement& pl : placements()) {
    // An axis-aligned square, a tilted parallelogram and a tilted trapezoid.
    Vec3f t, b;
    orthonormal_basis(normalize(Vec3f(0.3f, -0.8f, 0.52f)), t, b);
    const Vec3f c = pl.offset;
    const float s = pl.scale;
    const Quad quads[] = {
        {{c + s * Vec3f(-1, -1, 0), c + s * Vec3f(1, -1, 0), c + s * Vec3f(1, 1, 0), c + s * Vec3f(-1, 1, 0)}},
        {{c - s * t - s * b, c + s * t - s * b, c + s * t + s * b, c - s * t + s * b}},
        {{c - s * t - s * b, c + s * t - s * b, c + 0.5f * s * t + s * b, c - 0.5f * s * t + s * b}},
    };
    for (const Quad& q : quads) {
      check_planar(
          rng, pl, c, [&](const Ray& r, PrimHit& h) { return intersect(q, r, h); },
          [&](const Ray& r, const PrimHit& h) { return surface(q, r, h); });
    }
  }
}

TEST(SelfIntersection, TrianglesAtEveryScale) {
  test::Rng rng(23);
  for (const Placement& pl : placements()) {
    TriangleMesh m;
    const Vec3f c = pl.offset;
    m.positions = {c + pl.scale * Vec3f(-1.1f, -0.9f, 0.3f), c + pl.scale * Vec3f(1.3f, -0.7f, -0.2f),
                   c + pl.scale * Vec3f(0.1f, 1.2f, 0.4f)};
    m.indices = {0, 1, 2};
    check_planar(
        rng, pl, c, [&](const Ray& r, PrimHit& h) { return intersect(m, 0, r, h); },
        [&](const Ray& r, const PrimHit& h) { return surface(m, 0, r, h); });
  }
}

// A convex solid of parts (the cylinder, the cone; PrimHit::uv.x is the
// part): rays leaving never re-hit it, rays entering reach the far side.
template <class S>
void check_capped_solid(test::Rng& rng, const Placement& pl, const S& c) {
  int rehits = 0, leaks = 0, samples = 0;
  for (int i = 0; i < kPoints; ++i) {
    const Ray cam = probe(rng, 0.5f * (c.p0 + c.p1), pl.scale, 1.0f);
    PrimHit hit;
    if (!intersect(c, cam, hit)) continue;
    const SurfaceGeometry sg = surface(c, cam, hit);
    for (int k = 0; k < kDirections; ++k) {
      ++samples;
      const Vec3f w = rng.hemisphere(sg.ng, kMinCos);
      PrimHit h;
      if (intersect(c, spawn_ray(sg, w), h)) ++rehits;
      const Ray in = spawn_ray(sg, -w);
      if (!intersect(c, in, h)) {
        ++leaks;
      } else if (h.uv.x == hit.uv.x && h.t < 1e-4f * pl.scale) {
        ++rehits;  // the same part right where the ray started
      }
    }
  }
  EXPECT_GT(samples, kPoints * kDirections / 4) << pl.name();
  EXPECT_EQ(rehits, 0) << pl.name();
  EXPECT_EQ(leaks, 0) << pl.name();
}

TEST(SelfIntersection, CylindersAtEveryScale) {
  test::Rng rng(24);
  for (const Placement& pl : placements()) {
    const Vec3f p0 = pl.offset + pl.scale * Vec3f(0.2f, -0.1f, 0.3f);
    const Cylinder c{p0, p0 + 2.0f * pl.scale * normalize(Vec3f(0.4f, 0.9f, -0.3f)), 0.5f * pl.scale};
    check_capped_solid(rng, pl, c);
  }
}

TEST(SelfIntersection, ConesAtEveryScale) {
  test::Rng rng(26);
  for (const Placement& pl : placements()) {
    const Vec3f p0 = pl.offset + pl.scale * Vec3f(0.2f, -0.1f, 0.3f);
    const Vec3f p1 = p0 + 2.0f * pl.scale * normalize(Vec3f(0.4f, 0.9f, -0.3f));
    check_capped_solid(rng, pl, Cone{p0, p1, 0.7f * pl.scale, 0.0f});
    check_capped_solid(rng, pl, Cone{p0, p1, 0.7f * pl.scale, 0.3f * pl.scale});
  }
}

// Discs (and annuli), polygons and infinite planes are double-sided like quads.
TEST(SelfIntersection, DiscsPolygonsAndPlanesAtEveryScale) {
  test::Rng rng(27);
  for (const Placement& pl : placements()) {
    const Vec3f c = pl.offset;
    const float s = pl.scale;
    const Vec3f n = normalize(Vec3f(0.3f, -0.8f, 0.52f));
    for (const float inner : {0.0f, 0.3f}) {
      const Disc d = make_disc(c, n, 1.2f * s, inner * s);
      check_planar(
          rng, pl, c, [&](const Ray& r, PrimHit& h) { return intersect(d, r, h); },
          [&](const Ray& r, const PrimHit& h) { return surface(d, r, h); });
    }
    Vec3f t, b;
    orthonormal_basis(n, t, b);
    const ConvexPolygon p = make_polygon({c - s * t - s * b, c + s * t - s * b, c + 1.3f * s * t + 0.2f * s * b,
                                          c + 0.5f * s * t + s * b, c - 0.8f * s * t + 0.7f * s * b});
    check_planar(
        rng, pl, c, [&](const Ray& r, PrimHit& h) { return intersect(p, r, h); },
        [&](const Ray& r, const PrimHit& h) { return surface(p, r, h); });
    const InfinitePlane plane = make_plane(c, n, {}, 1.0f);
    check_planar(
        rng, pl, c, [&](const Ray& r, PrimHit& h) { return intersect(plane, 0, r, h); },
        [&](const Ray& r, const PrimHit& h) { return surface(plane, 0, r, h); });
  }
}

TEST(SelfIntersection, MeshesAtEveryScale) {
  test::Rng rng(25);
  for (const Placement& pl : placements()) {
    const TriangleMesh m = test::make_uv_sphere(pl.offset, pl.scale, 12, 24);
    int rehits = 0, leaks = 0, samples = 0;
    for (int i = 0; i < kPoints / 3; ++i) {
      const Ray cam = probe(rng, pl.offset, pl.scale, 0.9f);
      PrimHit hit;
      uint32_t prim = 0;
      if (!mesh_hit(m, cam, hit, prim)) continue;
      const SurfaceGeometry sg = surface(m, prim, cam, hit);
      for (int k = 0; k < kDirections; ++k) {
        ++samples;
        const Vec3f w = rng.hemisphere(sg.ng, kMinCos);
        PrimHit h;
        uint32_t p = 0;
        if (mesh_hit(m, spawn_ray(sg, w), h, p)) ++rehits;  // convex polyhedron
        if (!mesh_hit(m, spawn_ray(sg, -w), h, p)) {
          ++leaks;
        } else if (p == prim) {
          ++rehits;
        }
      }
    }
    EXPECT_GT(samples, kPoints / 6 * kDirections) << pl.name();
    EXPECT_EQ(rehits, 0) << pl.name();
    EXPECT_EQ(leaks, 0) << pl.name();
  }
}

TEST(SelfIntersection, ContactShadowsSurvive) {
  // A unit sphere resting on a floor quad at y = 0.
  const Quad floor{{{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}}};
  const Sphere ball{{0, 1, 0}, 1.0f};
  const Vec3f eye{3, 2, 4};
  auto floor_point = [&](Vec3f target) {
    const Ray cam{eye, target - eye};
    PrimHit hit;
    EXPECT_TRUE(intersect(floor, cam, hit));
    return surface(floor, cam, hit);
  };
  PrimHit h;
  // 1e-3 from the contact point the ball is only 5e-7 above the floor.
  for (Vec3f target : {Vec3f(1e-3f, 0, 0), Vec3f(0, 0, -1e-3f), Vec3f(2e-4f, 0, 2e-4f)}) {
    const SurfaceGeometry sg = floor_point(target);
    EXPECT_TRUE(intersect(ball, spawn_ray_to(sg, sg.p + Vec3f(0, 10, 0)), h)) << target.x;
    EXPECT_TRUE(intersect(ball, spawn_ray(sg, {0.1f, 1, 0.05f}), h));
  }
  // A ball hovering 1e-3 above the floor still shadows the point beneath it,
  // and the point 1e-3 away from beneath it, towards a light above.
  const Sphere hovering{{0, 1.001f, 0}, 1.0f};
  for (Vec3f target : {Vec3f(0, 0, 0), Vec3f(1e-3f, 0, 0)}) {
    const SurfaceGeometry sg = floor_point(target);
    const Ray shadow = spawn_ray_to(sg, {0.3f, 10, 0.2f});
    ASSERT_TRUE(intersect(hovering, shadow, h));
    EXPECT_NEAR(h.t * length(shadow.dir), 1e-3f, 2e-5f);
  }
  // And a point well beside the ball is lit.
  const SurfaceGeometry lit = floor_point({2, 0, 0});
  EXPECT_FALSE(intersect(ball, spawn_ray_to(lit, {2, 10, 0}), h));
}

// ---------------------------------------------------------------- leaks
int count_escapes_from(const TriangleMesh& m, Vec3f origin, const std::vector<Vec3f>& targets) {
  int escapes = 0;
  for (const Vec3f& t : targets) {
    PrimHit hit;
    uint32_t prim = 0;
    if (!mesh_hit(m, Ray{origin, t - origin}, hit, prim)) ++escapes;
  }
  return escapes;
}

// Every vertex, and points on every edge (midpoints and random), of a mesh.
std::vector<Vec3f> edge_and_vertex_targets(const TriangleMesh& m, test::Rng& rng) {
  std::vector<Vec3f> out(m.positions.begin(), m.positions.end());
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    for (int e = 0; e < 3; ++e) {
      const Vec3f a = m.positions[m.indices[i + e]];
      const Vec3f b = m.positions[m.indices[i + (e + 1) % 3]];
      out.push_back(0.5f * (a + b));
      const float s = rng.uniform();
      out.push_back((1 - s) * a + s * b);
    }
  }
  return out;
}

TEST(Watertight, ClosedMeshesDoNotLeakAtEdgesAndVertices) {
  test::Rng rng(31);
  const Vec3f c{0.3f, -0.2f, 0.7f};
  const TriangleMesh meshes[] = {test::make_uv_sphere(c, 1.3f, 16, 32), test::make_uv_sphere(c, 1e-3f, 8, 16),
                                 test::make_uv_sphere(c + Vec3f(5e3f, 0, 0), 10.0f, 16, 32),
                                 test::make_box_mesh(c - Vec3f(1.0f, 0.5f, 0.25f), c + Vec3f(0.7f, 1.5f, 2.0f))};
  for (const TriangleMesh& m : meshes) {
    const std::vector<Vec3f> targets = edge_and_vertex_targets(m, rng);
    const Bounds3f b = bounds(Shape{m});
    const Vec3f centre = b.centre();
    EXPECT_EQ(count_escapes_from(m, centre, targets), 0);
    for (int k = 0; k < 5; ++k) {
      const Vec3f inside = centre + 0.2f * (b.extent() * rng.unit_vector());
      EXPECT_EQ(count_escapes_from(m, inside, targets), 0);
    }
    // Many random directions too.
    int escapes = 0;
    for (int i = 0; i < 20000; ++i) {
      PrimHit hit;
      uint32_t prim = 0;
      if (!mesh_hit(m, Ray{centre, rng.unit_vector()}, hit, prim)) ++escapes;
    }
    EXPECT_EQ(escapes, 0);
  }
}

TEST(Watertight, BoxOfQuadsDoesNotLeak) {
  test::Rng rng(32);
  const Vec3f lo{-0.7f, 0.1f, -1.3f}, hi{0.9f, 2.2f, 0.4f};
  std::vector<Quad> faces;
  for (int f = 0; f < 6; ++f) faces.push_back(test::box_face_quad(lo, hi, f));
  std::vector<Vec3f> targets;
  for (const Quad& q : faces) {
    for (int k = 0; k < 4; ++k) {
      targets.push_back(q.v[k]);
      targets.push_back(0.5f * (q.v[k] + q.v[(k + 1) % 4]));
      const float s = rng.uniform();
      targets.push_back((1 - s) * q.v[k] + s * q.v[(k + 1) % 4]);
    }
    targets.push_back(0.5f * (q.v[0] + q.v[2]));  // on the diagonal
  }
  const Vec3f centre = 0.5f * (lo + hi);
  int escapes = 0;
  for (int k = 0; k < 6; ++k) {
    const Vec3f origin = k == 0 ? centre : centre + 0.3f * rng.unit_vector();
    for (const Vec3f& t : targets) {
      bool any = false;
      for (const Quad& q : faces) {
        PrimHit h;
        any = any || intersect(q, Ray{origin, t - origin}, h);
      }
      if (!any) ++escapes;
    }
  }
  EXPECT_EQ(escapes, 0);
}

TEST(Watertight, CylinderDoesNotLeakAtTheRims) {
  test::Rng rng(33);
  const Cylinder c{{0.1f, 0.2f, 0.3f}, {0.9f, 2.1f, -0.4f}, 0.45f};
  const Vec3f axis = normalize(c.p1 - c.p0);
  Vec3f e0, e1;
  orthonormal_basis(axis, e0, e1);
  int escapes = 0;
  for (int i = 0; i < 20000; ++i) {
    const float phi = rng.uniform(0.0f, 2.0f * kPi);
    const Vec3f rim = (i % 2 ? c.p1 : c.p0) + c.radius * (std::cos(phi) * e0 + std::sin(phi) * e1);
    const Vec3f origin = 0.5f * (c.p0 + c.p1) + 0.2f * c.radius * rng.unit_vector();
    PrimHit h;
    if (!intersect(c, Ray{origin, rim - origin}, h)) ++escapes;
  }
  EXPECT_EQ(escapes, 0);
}

// Rays from inside aimed exactly at the rims (and the apex) of cones: none
// escapes between side and cap.
TEST(Watertight, ConeDoesNotLeakAtTheRimsOrTheApex) {
  test::Rng rng(34);
  for (const float top : {0.0f, 0.2f}) {
    const Cone c{{0.1f, 0.2f, 0.3f}, {0.9f, 2.1f, -0.4f}, 0.45f, top};
    const Vec3f axis = normalize(c.p1 - c.p0);
    Vec3f e0, e1;
    orthonormal_basis(axis, e0, e1);
    int escapes = 0;
    for (int i = 0; i < 20000; ++i) {
      const float phi = rng.uniform(0.0f, 2.0f * kPi);
      const Vec3f rim = (i % 2 ? c.p1 : c.p0) + (i % 2 ? top : c.radius) * (std::cos(phi) * e0 + std::sin(phi) * e1);
      const Vec3f origin = c.p0 + 0.3f * (c.p1 - c.p0) + 0.1f * c.radius * rng.unit_vector();
      PrimHit h;
      if (!intersect(c, Ray{origin, rim - origin}, h)) ++escapes;
    }
    EXPECT_EQ(escapes, 0) << "top radius " << top;
  }
}

}  // namespace
}  // namespace pt

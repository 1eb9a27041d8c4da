// Self-intersection across scales, for every backend: random spheres and
// triangles whose coordinates and sizes are log-uniform over 1e-4 .. 1e4; a ray
// spawned from a surface point never re-hits the surface it leaves, on either
// side. And contact shadows stay at every scale: floor points under a sphere
// resting on the floor and under a box standing on it are shadowed, points
// beside them are lit. (The per-routine version of these checks, without a
// backend, is tests/geometry/test_self_intersection.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "backends.h"
#include "stability_util.h"

namespace pt {
namespace {

using SelfIntersection = test::PerBackend;
using ContactShadows = test::PerBackend;

constexpr float kLoExp = -4.0f, kHiExp = 4.0f;  // 1e-4 .. 1e4
constexpr float kMinCos = 1e-3f;                // spawned directions up to 89.94 degrees from the normal

struct RandomScene {
  SceneGeometry geometry;
  std::vector<float> size;  // characteristic size of each shape (radius, or triangle extent)
  std::size_t soup = 0;     // index of the triangle soup
};

RandomScene random_scene(test::Rng& rng, int spheres, int triangles) {
  RandomScene s;
  for (int i = 0; i < spheres; ++i) {
    const float r = test::log_uniform(rng, kLoExp, kHiExp);
    s.geometry.shapes.push_back(Sphere{test::log_uniform_point(rng, kLoExp, kHiExp), r, {0, 0, 1}});
    s.size.push_back(r);
  }
  TriangleMesh soup;
  for (int i = 0; i < triangles; ++i) {
    const Vec3f c = test::log_uniform_point(rng, kLoExp, kHiExp);
    const float size = test::log_uniform(rng, kLoExp, kHiExp);
    for (int k = 0; k < 3; ++k) soup.positions.push_back(c + size * rng.unit_vector());
    for (uint32_t k = 0; k < 3; ++k) soup.indices.push_back(static_cast<uint32_t>(3 * i) + k);
  }
  s.soup = s.geometry.shapes.size();
  s.geometry.shapes.push_back(std::move(soup));
  s.size.push_back(0.0f);
  return s;
}

// A ray from outside a shape of size `size` around `centre`, aimed at a random point near it.
Ray probe(test::Rng& rng, Vec3f target, float size) {
  const Vec3f origin = target + 5.0f * size * rng.unit_vector();
  return Ray{origin, normalize(target - origin)};
}

// Follows `ray` through whatever lies in front until it reaches (shape, prim):
// the random shapes overlap (a sphere of radius 1e4 holds most of the others).
// On success `ray` ends with tmin at the previous surface, as a camera ray would
// have arrived there through transparent surfaces.
bool first_hit_on(const Accelerator& accel, Ray& ray, std::size_t shape, uint32_t prim, Hit& hit) {
  for (int step = 0; step < 64; ++step) {
    if (!accel.intersect(ray, hit)) return false;
    if (hit.shape == shape && hit.prim == prim) return true;
    ray.tmin = hit.t;
  }
  return false;
}

TEST_P(SelfIntersection, LogUniformSpheresAndTrianglesNeverReHitThemselves) {
  test::Rng rng(7001);
  const RandomScene scene = random_scene(rng, 150, 150);
  WorkerPool pool(2);
  std::unique_ptr<Accelerator> accel;
  build(scene.geometry, pool, accel);
  if (!accel) return;
  const auto& soup = std::get<TriangleMesh>(scene.geometry.shapes[scene.soup]);

  int sphere_points = 0, triangle_points = 0, rehits = 0, short_chords = 0, inward_checked = 0;
  for (int round = 0; round < 10; ++round) {
    // Every sphere, and every triangle of the soup, in turn.
    for (std::size_t target_index = 0; target_index < scene.soup + soup.triangle_count(); ++target_index) {
      const std::size_t shape = std::min(target_index, scene.soup);
      const auto prim = static_cast<uint32_t>(target_index - shape);
      Vec3f target;
      float size = 0;
      if (shape == scene.soup) {
        const Vec3f a = soup.positions[3 * prim], b = soup.positions[3 * prim + 1], c = soup.positions[3 * prim + 2];
        const float u = rng.uniform(), v = rng.uniform() * (1 - u);
        target = a + u * (b - a) + v * (c - a);
        size = std::max(length(b - a), length(c - a));
      } else {
        const auto& s = std::get<Sphere>(scene.geometry.shapes[shape]);
        target = s.center + 0.9f * s.radius * rng.uniform() * rng.unit_vector();
        size = s.radius;
      }
      Ray cam = probe(rng, target, size);
      Hit hit;
      if (!first_hit_on(*accel, cam, shape, prim, hit)) continue;
      const SurfaceGeometry sg = surface(scene.geometry.shapes[shape], hit.prim, cam, PrimHit{hit.t, hit.uv});
      ASSERT_TRUE(is_finite(sg.p) && is_finite(sg.ng));
      const bool sphere = shape != scene.soup;
      (sphere ? sphere_points : triangle_points) += 1;
      for (int k = 0; k < 4; ++k) {
        const Vec3f w = rng.hemisphere(sg.ng, kMinCos);  // the side of ng
        for (const Vec3f dir : {w, -w}) {
          Hit h;
          const Ray r = spawn_ray(sg, dir);
          if (!accel->intersect(r, h) || h.shape != shape) continue;
          if (!sphere) {
            if (h.prim == hit.prim) ++rehits;  // a plane is never hit again
            continue;
          }
          if (dot(dir, sg.ng) > 0) {
            ++rehits;  // leaving a convex shape outward never hits it again
            continue;
          }
          // Inward: the far side, one chord (2 r cos) away, not the point we left.
          const auto& s = std::get<Sphere>(scene.geometry.shapes[shape]);
          const float chord = 2.0f * s.radius * std::fabs(dot(normalize(dir), sg.ng));
          // A chord shorter than the position's own error bound is below the
          // float resolution at that point (a sphere a few ulps across).
          if (chord < 8.0f * length(sg.p_error)) continue;
          ++inward_checked;
          if (h.t * length(r.dir) < 0.5f * chord) ++short_chords;
        }
      }
    }
  }
  EXPECT_GT(sphere_points, 1000);
  EXPECT_GT(triangle_points, 1000);
  EXPECT_EQ(rehits, 0);
  EXPECT_GT(inward_checked, 2000);
  EXPECT_EQ(short_chords, 0);
}

// A floor (a quad, or a two-triangle mesh) with a sphere resting on it and a box
// mesh standing on it, built at `scale` around `offset`.
SceneGeometry floor_scene(float scale, Vec3f offset, bool floor_is_mesh) {
  SceneGeometry g;
  const Vec3f c[4] = {offset + scale * Vec3f(-10, 0, -10), offset + scale * Vec3f(-10, 0, 10),
                      offset + scale * Vec3f(10, 0, 10), offset + scale * Vec3f(10, 0, -10)};
  if (floor_is_mesh) {
    TriangleMesh m;
    m.positions.assign(c, c + 4);
    m.indices = {0, 1, 2, 0, 2, 3};
    g.shapes.push_back(std::move(m));
  } else {
    g.shapes.push_back(Quad{{c[0], c[1], c[2], c[3]}});
  }
  g.shapes.push_back(Sphere{offset + scale * Vec3f(0, 1, 0), scale, {0, 1, 0}});
  g.shapes.push_back(test::make_box_mesh(offset + scale * Vec3f(2, 0, -0.5f), offset + scale * Vec3f(3, 1, 0.5f)));
  return g;
}

bool floor_hit(const Shape& floor, const Ray& ray, PrimHit& hit, uint32_t& prim) {
  if (const auto* q = std::get_if<Quad>(&floor)) return intersect(*q, ray, hit);
  const auto& m = std::get<TriangleMesh>(floor);
  for (prim = 0; prim < m.triangle_count(); ++prim) {
    if (intersect(m, prim, ray, hit)) return true;
  }
  return false;
}

TEST_P(ContactShadows, StayAtEveryScale) {
  test::Rng rng(7002);
  WorkerPool pool(2);
  int shadowed = 0, lit = 0, cases = 0;
  for (int i = 0; i < 40; ++i) {
    const float scale = test::log_uniform(rng, kLoExp, kHiExp);
    // Up to 1000 sizes from the origin, where a float keeps ~14 bits below the size.
    const Vec3f offset = scale * test::log_uniform(rng, 0.0f, 3.0f) * rng.unit_vector();
    const SceneGeometry g = floor_scene(scale, offset, i % 2 == 1);
    std::unique_ptr<Accelerator> accel;
    build(g, pool, accel);
    if (!accel) return;
    // Floor points (relative to the offset, in units of scale) and whether a
    // light straight above each must be blocked.
    struct Probe {
      Vec3f at;
      bool blocked;
    };
    std::vector<Probe> probes = {
        {{1e-3f, 0, 0}, true},        // beside the sphere's contact point
        {{0, 0, -1e-3f}, true},
        {{0.5f, 0, 0.3f}, true},      // under the sphere
        {{2.5f, 0, 0}, true},         // under the box
        {{2.001f, 0, 0.499f}, true},  // under the box, near its corner
        {{1.99f, 0, 0}, false},       // just beside the box: the light above is not blocked
        {{3.01f, 0, 0.2f}, false},
        {{-5, 0, 5}, false},          // open floor
    };
    for (int k = 0; k < 4; ++k) probes.push_back({{rng.uniform(2.05f, 2.95f), 0, rng.uniform(-0.45f, 0.45f)}, true});
    for (const Probe& p : probes) {
      const Vec3f target = offset + scale * p.at;
      // The floor point, found with the floor's own routine (the box's bottom
      // face lies in the floor's plane, so a backend may return either).
      const Ray cam{target + scale * Vec3f(0.3f, -5, 0.2f), scale * Vec3f(-0.3f, 5, -0.2f)};  // from below
      PrimHit hit;
      uint32_t prim = 0;
      ASSERT_TRUE(floor_hit(g.shapes[0], cam, hit, prim)) << "scale " << scale;
      const SurfaceGeometry sg = surface(g.shapes[0], prim, cam, hit);
      const Vec3f light = sg.p + scale * Vec3f(0, 10, 0);
      ++cases;
      const bool blocked = accel->occluded(spawn_ray_to(sg, light));
      EXPECT_EQ(blocked, p.blocked) << "scale " << scale << " offset " << offset.x << "," << offset.y << ","
                                    << offset.z << " probe " << p.at.x << "," << p.at.z;
      (blocked ? shadowed : lit) += 1;
    }
  }
  EXPECT_EQ(cases, 40 * 12);
}

INSTANTIATE_TEST_SUITE_P(Backends, SelfIntersection, ::testing::ValuesIn(accel_kind_names()),
                         test::backend_test_name);
INSTANTIATE_TEST_SUITE_P(Backends, ContactShadows, ::testing::ValuesIn(accel_kind_names()),
                         test::backend_test_name);

}  // namespace
}  // namespace pt

// The Embree backend against a brute-force loop over the same geometry
// routines, plus robustness: non-finite rays, open intervals, leaks and acne.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include <tbb/parallel_for.h>

#include "accel/accelerator.h"
#include "brute_force.h"
#include "core/parallel.h"
#include "../geometry/test_util.h"

namespace pt {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

SceneGeometry every_shape_scene() {
  SceneGeometry g;
  test::Rng rng(41);
  for (int i = 0; i < 12; ++i) {
    const Vec3f c{rng.uniform(-8, 8), rng.uniform(-8, 8), rng.uniform(-8, 8)};
    switch (i % 4) {
      case 0: g.shapes.push_back(Sphere{c, rng.uniform(0.3f, 1.5f), {0, 0, 1}}); break;
      case 1: {
        Vec3f t, b;
        orthonormal_basis(rng.unit_vector(), t, b);
        const float s = rng.uniform(0.5f, 2.0f);
        g.shapes.push_back(Quad{{c - s * t - s * b, c + s * t - s * b, c + s * t + 0.5f * s * b, c - s * t + s * b}});
        break;
      }
      case 2: g.shapes.push_back(Cylinder{c, c + rng.uniform(0.5f, 3.0f) * rng.unit_vector(), rng.uniform(0.2f, 1.0f)}); break;
      default: {
        TriangleMesh m = (i % 8 == 3) ? test::make_uv_sphere(c, rng.uniform(0.5f, 2.0f), 8, 16)
                                      : test::make_box_mesh(c - Vec3f(0.7f, 0.4f, 1.0f), c + Vec3f(0.5f, 0.9f, 0.3f));
        g.shapes.push_back(std::move(m));
      }
    }
  }
  // A triangle soup and a ground quad.
  TriangleMesh soup;
  for (int i = 0; i < 60; ++i) {
    const Vec3f c{rng.uniform(-9, 9), rng.uniform(-9, 9), rng.uniform(-9, 9)};
    for (int k = 0; k < 3; ++k) soup.positions.push_back(c + rng.uniform(0.2f, 1.2f) * rng.unit_vector());
    for (uint32_t k = 0; k < 3; ++k) soup.indices.push_back(3 * i + k);
  }
  soup.positions.shrink_to_fit();  // exercises the copied (unshared) vertex buffer
  g.shapes.push_back(std::move(soup));
  g.shapes.push_back(Quad{{{-20, -10, -20}, {-20, -10, 20}, {20, -10, 20}, {20, -10, -20}}});
  return g;
}

std::unique_ptr<Accelerator> build(const SceneGeometry& g, WorkerPool& pool) {
  Diagnostics diag;
  auto accel = build_accelerator(AccelKind::Embree, g, pool, diag);
  EXPECT_FALSE(diag.has_errors()) << diag.format();
  return accel;
}

TEST(Embree, NearestHitAndOcclusionMatchBruteForce) {
  const SceneGeometry g = every_shape_scene();
  WorkerPool pool(2);
  auto accel = build(g, pool);
  ASSERT_NE(accel, nullptr);
  test::Rng rng(42);
  int hits = 0, mismatches = 0;
  for (int i = 0; i < 20000; ++i) {
    Ray ray{{rng.uniform(-12, 12), rng.uniform(-12, 12), rng.uniform(-12, 12)},
            rng.uniform(0.1f, 3.0f) * rng.unit_vector()};
    if (i % 3 == 0) ray.tmax = rng.uniform(0.5f, 10.0f);
    if (i % 5 == 0) ray.tmin = rng.uniform(0.0f, 2.0f);
    Hit expected, got;
    const bool want = test::brute_intersect(g, ray, expected);
    const bool have = accel->intersect(ray, got);
    EXPECT_EQ(accel->occluded(ray), want) << i;
    if (want != have) {
      ++mismatches;
      continue;
    }
    if (!want) continue;
    ++hits;
    EXPECT_EQ(got.shape, expected.shape) << i;
    EXPECT_EQ(got.prim, expected.prim) << i;
    EXPECT_NEAR(got.t, expected.t, 1e-5f * expected.t) << i;
    if (!std::holds_alternative<TriangleMesh>(g.shapes[got.shape])) {
      EXPECT_EQ(got.uv, expected.uv);
    } else {
      EXPECT_NEAR(got.uv.x, expected.uv.x, 1e-4f);
      EXPECT_NEAR(got.uv.y, expected.uv.y, 1e-4f);
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 3000);
}

TEST(Embree, ParallelQueriesMatchSerialOnes) {
  const SceneGeometry g = every_shape_scene();
  WorkerPool pool(2);
  auto accel = build(g, pool);
  ASSERT_NE(accel, nullptr);
  test::Rng rng(43);
  std::vector<Ray> rays;
  for (int i = 0; i < 20000; ++i) rays.push_back(Ray{{rng.uniform(-12, 12), 0, rng.uniform(-12, 12)}, rng.unit_vector()});
  std::vector<Hit> serial(rays.size());
  std::vector<char> serial_hit(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) serial_hit[i] = accel->intersect(rays[i], serial[i]);
  std::atomic<int> different{0};
  pool.run([&] {
    tbb::parallel_for(std::size_t{0}, rays.size(), [&](std::size_t i) {
      Hit h;
      const bool hit = accel->intersect(rays[i], h);
      if (hit != static_cast<bool>(serial_hit[i]) || (hit && (h.t != serial[i].t || h.shape != serial[i].shape))) {
        ++different;
      }
    });
  });
  EXPECT_EQ(different.load(), 0);
}

TEST(Embree, NonFiniteRaysMissWithoutCrashing) {
  const SceneGeometry g = every_shape_scene();
  WorkerPool pool(2);
  auto accel = build(g, pool);
  ASSERT_NE(accel, nullptr);
  const float inf = kInfinity;
  const Ray rays[] = {
      {{kNaN, 0, 0}, {0, 0, 1}},    {{0, 0, 0}, {kNaN, 0, 1}},         {{0, inf, 0}, {0, 0, 1}},
      {{0, 0, 0}, {0, -inf, 1}},    {{0, 0, 0}, {0, 0, 0}},            {{0, 0, 0}, {0, -1, 0}, kNaN, inf},
      {{0, 0, 0}, {0, -1, 0}, 0.0f, kNaN}, {{0, 0, 0}, {0, -1, 0}, 5.0f, 1.0f}, {{0, 0, 0}, {0, -1, 0}, inf, inf},
  };
  for (const Ray& r : rays) {
    Hit hit;
    EXPECT_FALSE(accel->intersect(r, hit));
    EXPECT_FALSE(accel->occluded(r));
  }
  // Sanity: the same ray with finite values hits the ground.
  Hit hit;
  EXPECT_TRUE(accel->intersect(Ray{{0, 0, 0}, {0, -1, 0}}, hit));
}

TEST(Embree, IntervalIsOpenOnBothEndsForEveryShapeType) {
  WorkerPool pool(1);
  SceneGeometry g;
  g.shapes.push_back(Sphere{{0, 0, 10}, 1.0f});
  g.shapes.push_back(Quad{{{-1, -1, 20}, {1, -1, 20}, {1, 1, 20}, {-1, 1, 20}}});
  g.shapes.push_back(Cylinder{{0, -1, 30}, {0, 1, 30}, 1.0f});
  TriangleMesh m;
  m.positions = {{-1, -1, 40}, {1, -1, 40}, {0, 1, 40}};
  m.indices = {0, 1, 2};
  g.shapes.push_back(m);
  auto accel = build(g, pool);
  ASSERT_NE(accel, nullptr);
  for (uint32_t shape = 0; shape < 4; ++shape) {
    // Start just past the previous shape so this one is the nearest.
    const Ray base{{0.1f, 0.05f, 5.0f + 10.0f * static_cast<float>(shape)}, {0, 0, 1}};
    Hit hit;
    ASSERT_TRUE(accel->intersect(base, hit));
    ASSERT_EQ(hit.shape, shape);
    const float t = hit.t;
    Ray r = base;
    r.tmax = t;
    EXPECT_FALSE(accel->intersect(r, hit)) << shape;
    EXPECT_FALSE(accel->occluded(r)) << shape;
    r.tmax = std::nextafter(t, kInfinity);
    EXPECT_TRUE(accel->intersect(r, hit)) << shape;
    EXPECT_TRUE(accel->occluded(r)) << shape;
    r = base;
    r.tmin = t;
    if (shape < 3) {
      ASSERT_TRUE(accel->intersect(r, hit));  // the next surface along the ray
      EXPECT_GT(hit.t, t) << shape;
    } else {
      EXPECT_FALSE(accel->intersect(r, hit));  // the last one
    }
  }
}

TEST(Embree, ClosedMeshesDoNotLeakThroughEdges) {
  WorkerPool pool(2);
  test::Rng rng(44);
  const Vec3f c{0.3f, -0.2f, 0.7f};
  for (const TriangleMesh& mesh : {test::make_uv_sphere(c, 1.3f, 24, 48), test::make_uv_sphere(c, 1e-3f, 8, 16),
                                   test::make_box_mesh(c - Vec3f(1.0f, 0.5f, 0.25f), c + Vec3f(0.7f, 1.5f, 2.0f))}) {
    SceneGeometry g;
    g.shapes.push_back(mesh);
    auto accel = build(g, pool);
    ASSERT_NE(accel, nullptr);
    std::vector<Vec3f> edge_targets;
    for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
      for (int e = 0; e < 3; ++e) {
        const Vec3f a = mesh.positions[mesh.indices[i + e]];
        const Vec3f b = mesh.positions[mesh.indices[i + (e + 1) % 3]];
        edge_targets.push_back(0.5f * (a + b));
        const float s = rng.uniform();
        edge_targets.push_back((1 - s) * a + s * b);
      }
    }
    const Bounds3f box = accel->bounds();
    int escapes = 0, vertex_escapes = 0, vertex_rays = 0;
    for (int k = 0; k < 6; ++k) {
      const Vec3f origin = box.centre() + (k == 0 ? Vec3f(0.0f) : 0.2f * (box.extent() * rng.unit_vector()));
      for (const Vec3f& t : edge_targets) {
        Hit hit;
        if (!accel->intersect(Ray{origin, t - origin}, hit)) ++escapes;
        if (!accel->occluded(Ray{origin, t - origin})) ++escapes;
      }
      for (int i = 0; i < 5000; ++i) {
        Hit hit;
        if (!accel->intersect(Ray{origin, rng.unit_vector()}, hit)) ++escapes;
      }
      for (const Vec3f& v : mesh.positions) {
        Hit hit;
        ++vertex_rays;
        if (!accel->intersect(Ray{origin, v - origin}, hit)) ++vertex_escapes;
      }
    }
    EXPECT_EQ(escapes, 0);
    // Embree 3's robust triangle test is watertight on edges but not exactly at
    // vertices (RenderKit/embree issues 174, 181; docs/geometry.md): a ray aimed
    // exactly at a vertex rarely slips through. Our own routine has no such gap
    // (Watertight.ClosedMeshesDoNotLeakAtEdgesAndVertices).
    EXPECT_LE(vertex_escapes, vertex_rays / 100);
  }
}

TEST(Embree, SpawnedRaysDoNotReHitMeshesAtAnyScale) {
  WorkerPool pool(2);
  test::Rng rng(45);
  for (float scale : {1e-3f, 1e-1f, 1.0f, 1e2f, 1e4f}) {
    for (const Vec3f offset : {Vec3f(0.0f), scale * Vec3f(1000.0f, -700.0f, 300.0f)}) {
      SceneGeometry g;
      g.shapes.push_back(test::make_uv_sphere(offset, scale, 16, 32));
      auto accel = build(g, pool);
      ASSERT_NE(accel, nullptr);
      const auto& mesh = std::get<TriangleMesh>(g.shapes[0]);
      int rehits = 0, leaks = 0, samples = 0;
      for (int i = 0; i < 300; ++i) {
        const Vec3f target = offset + 0.9f * scale * rng.uniform() * rng.unit_vector();
        const Vec3f origin = target + 5.0f * scale * rng.unit_vector();
        const Ray cam{origin, normalize(target - origin)};
        Hit hit;
        if (!accel->intersect(cam, hit)) continue;
        const SurfaceGeometry sg = surface(g.shapes[0], hit.prim, cam, PrimHit{hit.t, hit.uv});
        for (int k = 0; k < 4; ++k) {
          ++samples;
          const Vec3f w = rng.hemisphere(sg.ng, 1e-3f);
          Hit h;
          if (accel->intersect(spawn_ray(sg, w), h)) ++rehits;  // convex: leaving never hits
          if (accel->occluded(spawn_ray_to(sg, sg.p + 2.0f * scale * w))) ++rehits;
          if (!accel->intersect(spawn_ray(sg, -w), h)) {
            ++leaks;
          } else if (h.prim == hit.prim) {
            ++rehits;
          }
        }
      }
      (void)mesh;
      EXPECT_GT(samples, 600);
      EXPECT_EQ(rehits, 0) << "scale " << scale << " offset " << offset.x;
      EXPECT_EQ(leaks, 0) << "scale " << scale << " offset " << offset.x;
    }
  }
}

TEST(Embree, ContactShadowUnderASphereOnAFloor) {
  SceneGeometry g;
  g.shapes.push_back(Quad{{{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}}});
  g.shapes.push_back(Sphere{{0, 1, 0}, 1.0f});
  g.shapes.push_back(test::make_uv_sphere({4, 1.001f, 0}, 1.0f, 32, 64));  // a mesh hovering 1e-3 above
  WorkerPool pool(2);
  auto accel = build(g, pool);
  ASSERT_NE(accel, nullptr);
  for (Vec3f target : {Vec3f(1e-3f, 0, 0), Vec3f(0, 0, 1e-3f), Vec3f(4, 0, 0), Vec3f(4.001f, 0, 0)}) {
    const Ray cam{target + Vec3f(0.3f, -5, 0.2f), Vec3f(-0.3f, 5, -0.2f)};  // from below the floor
    Hit hit;
    ASSERT_TRUE(accel->intersect(cam, hit));
    ASSERT_EQ(hit.shape, 0u);
    const SurfaceGeometry sg = surface(g.shapes[0], hit.prim, cam, PrimHit{hit.t, hit.uv});
    EXPECT_TRUE(accel->occluded(spawn_ray_to(sg, sg.p + Vec3f(0.2f, 10, 0.1f)))) << target.x;
  }
  const Ray cam{{2, -5, -2}, {0, 1, 0}};
  Hit hit;
  ASSERT_TRUE(accel->intersect(cam, hit));
  const SurfaceGeometry lit = surface(g.shapes[0], hit.prim, cam, PrimHit{hit.t, hit.uv});
  EXPECT_FALSE(accel->occluded(spawn_ray_to(lit, {2, 10, -2})));
}

TEST(Embree, SharedAndCopiedVertexBuffersAgree) {
  TriangleMesh shared = test::make_uv_sphere({0, 0, 0}, 1.0f, 8, 16);
  shared.positions.reserve(shared.positions.size() + 1);
  TriangleMesh copied = shared;
  copied.positions.shrink_to_fit();
  SceneGeometry a, b;
  a.shapes.push_back(shared);
  b.shapes.push_back(copied);
  WorkerPool pool(1);
  auto accel_a = build(a, pool);
  auto accel_b = build(b, pool);
  ASSERT_TRUE(accel_a && accel_b);
  test::Rng rng(46);
  for (int i = 0; i < 2000; ++i) {
    const Ray ray{3.0f * rng.unit_vector(), rng.unit_vector()};
    Hit ha, hb;
    ASSERT_EQ(accel_a->intersect(ray, ha), accel_b->intersect(ray, hb));
    EXPECT_EQ(ha.t, hb.t);
    EXPECT_EQ(ha.prim, hb.prim);
  }
}

}  // namespace
}  // namespace pt

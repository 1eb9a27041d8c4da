// The numerical-stability catalogue's transformed cases (docs/numerical-
// stability.md, section "Transforms and instances"), for every backend:
// spheres, cylinders, pointed and truncated cones and a closed box mesh, and
// the flat discs (annuli) and polygons, placed by instances whose transforms
// combine per-axis scales log-uniform over 1e-4 .. 1e4 with random rotations,
// mirrors (negative determinant) and translations far from the origin. A ray
// spawned from a surface point (the surface carried to world space as
// RenderScene::intersect carries it) never re-hits the surface it leaves on
// the way out (no acne; either side of a flat shape), and rays from inside the
// closed shapes never escape (no leaks).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "backends.h"
#include "stability_util.h"
#include "../geometry/test_util.h"

namespace pt {
namespace {

class TransformedSurfaces : public test::PerBackend {
 public:
  void build_for(const SceneGeometry& g, WorkerPool& pool, std::unique_ptr<Accelerator>& out) { build(g, pool, out); }
};

// A random placement: scale (log-uniform per axis within `spread` decades of
// a common log-uniform size), rotation, an optional mirror, and a translation
// up to `far` times the size.
Transform random_placement(test::Rng& rng, float spread, float far) {
  const double size = test::log_uniform(rng, -4.0f, 4.0f);
  double s[3];
  for (double& v : s) v = size * std::pow(10.0, spread * (rng.uniform() - 0.5f));
  if (rng.uniform() < 0.5f) s[0] = -s[0];  // mirrored
  const Vec3f axis = rng.unit_vector();
  const Vec3f t = far * static_cast<float>(size) * rng.unit_vector();
  return Transform(Affine::translate(t.x, t.y, t.z) * Affine::rotate(axis.x, axis.y, axis.z, 360.0 * rng.uniform()) *
                   Affine::scale(s[0], s[1], s[2]));
}

// Which shapes are placed: the smooth sphere alone, every closed shape (the
// sphere, a cylinder, a box mesh, a pointed and a truncated cone), or those
// and the flat ones (a disc, an annulus, a pentagon).
enum class Shapes { Sphere, Closed, ClosedAndFlat };
constexpr uint32_t kClosedShapes = 5;  // the closed shapes come first

SceneGeometry placed_shapes(test::Rng& rng, int count, float spread, float far, Shapes which) {
  SceneGeometry g;
  g.shapes.push_back(Sphere{{0, 0, 0}, 1.0f, {0, 1, 0}});
  if (which != Shapes::Sphere) {
    g.shapes.push_back(Cylinder{{0, 0, -1}, {0, 0, 1}, 1.0f});
    g.shapes.push_back(test::make_box_mesh({-1, -1, -1}, {1, 1, 1}));
    g.shapes.push_back(Cone{{0, 0, -1}, {0, 0, 1}, 1.0f, 0.0f});
    g.shapes.push_back(Cone{{0, 0, -1}, {0, 0, 1}, 1.0f, 0.4f});
  }
  if (which == Shapes::ClosedAndFlat) {
    g.shapes.push_back(make_disc({0, 0, 0}, {0, 0, 1}, 1.0f, 0.0f));
    g.shapes.push_back(make_disc({0, 0, 0}, {0, 0, 1}, 1.0f, 0.3f));
    g.shapes.push_back(make_polygon({{-1, -1, 0}, {1, -1, 0}, {1.2f, 0.4f, 0}, {0, 1, 0}, {-1.1f, 0.5f, 0}}));
  }
  const auto kinds = static_cast<uint32_t>(g.shapes.size());
  for (uint32_t i = 0; i < kinds; ++i) g.prototypes.push_back({i});
  for (int i = 0; i < count; ++i)
    g.instances.push_back(Instance{static_cast<uint32_t>(i) % kinds, random_placement(rng, spread, far)});
  return g;
}

// The distance, in the shape's own space, from a point of closed shape
// `proto` to its nearest sharp edge (a box's edges, a cap's rim, the apex).
float edge_distance(uint32_t proto, Vec3f p) {
  const float r = std::sqrt(p.x * p.x + p.y * p.y);
  auto rim = [&](float radius, float z) { return std::hypot(r - radius, p.z - z); };
  switch (proto) {
    case 1: return std::min(rim(1, -1), rim(1, 1));  // the cylinder
    case 2: {                                         // the box: its two largest |coordinates| at 1
      float a[3] = {std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)};
      std::sort(a, a + 3);
      return std::hypot(1 - a[2], 1 - a[1]);
    }
    case 3: return std::min(rim(1, -1), length(p - Vec3f(0, 0, 1)));  // the pointed cone, apex at z = 1
    case 4: return std::min(rim(1, -1), rim(0.4f, 1));                  // the truncated cone
    default: return kInfinity;                                          // the sphere
  }
}

// Whether the world boxes of placements i and j meet.
bool boxes_meet(const SceneGeometry& g, uint32_t i, uint32_t j) {
  auto box = [&](uint32_t k) {
    return g.instances[k].transform.bounds(bounds(g.shapes[g.prototypes[g.instances[k].prototype][0]]));
  };
  const Bounds3f a = box(i), b = box(j);
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}

// The world surface at a hit, as RenderScene::intersect computes it.
SurfaceGeometry world_surface(const SceneGeometry& g, const Ray& ray, const Hit& hit) {
  PrimHit h;
  h.t = hit.t;
  h.uv = hit.uv;
  const Transform& t = g.instances[hit.instance].transform;
  return to_world(surface(g.shapes[hit.shape], hit.prim, t.to_object(ray), h), t);
}

struct Tally {
  int points = 0, rehits = 0, leaks = 0;
  float farthest_leak = 0.0f;  // the largest edge_distance() of a leak
};

// Probes each instance from outside; at each surface point spawns a ray out
// (must not hit the same instance: all the shapes are convex or flat) and, for
// a closed shape, one in (must hit the same instance again). A flat shape is
// left to the side the probe came from or through it: neither may re-hit.
// Placements whose boxes meet another's are left out (a ray into one may
// rightly hit the other first), and so are points within 1e-3 of the shape's
// size of a sharp edge from the leak check: an inward direction there may
// leave through the other face at once, within the offset and the rounding of
// the origin (the edge limit of docs/numerical-stability.md, section 11).
Tally probe_instances(const SceneGeometry& g, const Accelerator& accel, test::Rng& rng) {
  std::vector<bool> alone(g.instances.size(), true);
  for (uint32_t i = 0; i < g.instances.size(); ++i)
    for (uint32_t j = i + 1; j < g.instances.size(); ++j)
      if (boxes_meet(g, i, j)) alone[i] = alone[j] = false;
  Tally tally;
  for (uint32_t i = 0; i < g.instances.size(); ++i) {
    if (!alone[i]) continue;
    const Transform& t = g.instances[i].transform;
    for (int k = 0; k < 40; ++k) {
      const Vec3f target = t.point(0.5f * rng.unit_vector());
      const float reach = length(t.vector(Vec3f(1, 1, 1))) * 4.0f;
      const Vec3f origin = target + reach * rng.unit_vector();
      const Ray ray{origin, target - origin};
      Hit hit;
      if (!accel.intersect(ray, hit) || hit.instance != i) continue;
      const SurfaceGeometry sg = world_surface(g, ray, hit);
      ++tally.points;
      Vec3f out = rng.unit_vector();
      if (dot(out, sg.ng) < 0.0f) out = -out;
      if (dot(out, sg.ng) < 1e-3f) continue;
      const bool closed = g.instances[i].prototype < kClosedShapes;
      if (!closed && rng.uniform() < 0.5f) out = -out;  // through the flat shape
      Hit again;
      if (accel.intersect(spawn_ray(sg, out), again) && again.instance == i) {
        ++tally.rehits;
      }
      const float edge = edge_distance(g.instances[i].prototype, t.inverse_point(sg.p));
      if (closed && edge >= 1e-3f && (!accel.intersect(spawn_ray(sg, -out), again) || again.instance != i)) {
        ++tally.leaks;
        tally.farthest_leak = std::max(tally.farthest_leak, edge);
        const Vec3f po = t.inverse_point(sg.p);
        std::cerr << "LEAK proto " << g.instances[i].prototype << " obj p " << po.x << " " << po.y << " " << po.z
                  << " scale " << length(t.vector(Vec3f(1, 1, 1))) << " dist " << length(sg.p) << " out.ng " << dot(out, sg.ng) << "\n";
      }
    }
  }
  return tally;
}

// Places `count` shapes (see placed_shapes) on the test's backend and probes them.
void check_placements(TransformedSurfaces& test_case, uint32_t seed, int count, float spread, float far,
                      int min_points, Shapes which) {
  test::Rng rng(seed);
  const SceneGeometry g = placed_shapes(rng, count, spread, far, which);
  WorkerPool pool(2);
  std::unique_ptr<Accelerator> accel;
  test_case.build_for(g, pool, accel);
  if (!accel) return;
  const Tally t = probe_instances(g, *accel, rng);
  EXPECT_GT(t.points, min_points);
  EXPECT_EQ(t.rehits, 0) << "of " << t.points;
  EXPECT_EQ(t.leaks, 0) << "of " << t.points;
}

TEST_P(TransformedSurfaces, AnisotropicScalesRotationsAndMirrorsNeitherReHitNorLeak) {
  // Instances far apart (translations up to 1e3 sizes) so that few hide another.
  check_placements(*this, 9101, 150, 2.0f, 1e3f, 2500, Shapes::Closed);
}

TEST_P(TransformedSurfaces, InstancesFarFromTheOrigin) {
  // Up to 1e4 sizes away: the translation dominates every transformed
  // coordinate (float spacing there is ~1e-3 of the size). A smooth shape
  // holds there; at a sharp edge (a box's, a cap's rim) the ray offset, grown
  // with the coordinates, reaches across the edge beyond ~1e3 sizes (LeakSweep).
  check_placements(*this, 9102, 60, 1.0f, 1e4f, 1000, Shapes::Sphere);
}

TEST_P(TransformedSurfaces, DiscsAnnuliAndPolygonsNeitherSideReHits) {
  check_placements(*this, 9103, 160, 2.0f, 1e3f, 2500, Shapes::ClosedAndFlat);
}

// The measurement behind the limits in docs/numerical-stability.md (section
// 11): 20 seeds x 60 placements of every shape (spread 1 decade) at 1e3, 3e3
// and 1e4 sizes from the origin; prints the probes, leaks and re-hits. Run with
// --gtest_also_run_disabled_tests --gtest_filter='*LeakSweep*'.
TEST_P(TransformedSurfaces, DISABLED_LeakSweep) {
  for (float far : {1e3f, 3e3f, 1e4f}) {
    Tally sum;
    for (uint32_t seed = 0; seed < 20; ++seed) {
      test::Rng rng(5000 + seed);
      const SceneGeometry g = placed_shapes(rng, 60, 1.0f, far, Shapes::ClosedAndFlat);
      WorkerPool pool(2);
      std::unique_ptr<Accelerator> accel;
      build(g, pool, accel);
      if (!accel) return;
      const Tally t = probe_instances(g, *accel, rng);
      sum.points += t.points;
      sum.leaks += t.leaks;
      sum.rehits += t.rehits;
      sum.farthest_leak = std::max(sum.farthest_leak, t.farthest_leak);
    }
    std::printf("%s: %g sizes from the origin: %d probes, %d leaks (the farthest %.2g from an edge), %d re-hits\n",
                GetParam().c_str(), far, sum.points, sum.leaks, sum.farthest_leak, sum.rehits);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, TransformedSurfaces, ::testing::ValuesIn(accel_kind_names()),
                         test::backend_test_name);

}  // namespace
}  // namespace pt

// The leaf tests every kernel ends in: the src/geometry routines (the same
// ones the Embree backend's user geometry calls), compiled for the baseline ISA.
#include <cmath>
#include <type_traits>
#include <variant>

#include "accel/bvh/analytic.h"
#include "accel/cutout.h"
#include "accel/bvh/kernels.h"
#include "accel/bvh/layout.h"
#include "accel/bvh/ray_frame.h"
#include "core/transform.h"
#include "geometry/float_util.h"
#include "geometry/shapes.h"

namespace pt::bvh {

static_assert(kGamma2 == fp::gamma(2) && kGamma3 == fp::gamma(3) && kGamma5 == fp::gamma(5),
              "the AVX2 triangle filter must use the reference routine's constants");

namespace {

Ray to_ray(const RayQuery& q) {
  return Ray{{q.org[0], q.org[1], q.org[2]}, {q.dir[0], q.dir[1], q.dir[2]}, q.tmin, q.tmax};
}

bool record(const PrimHit& h, uint32_t object, uint32_t prim, RayQuery& q, HitRecord& hit) {
  q.tmax = h.t;
  hit = HitRecord{h.t, object, prim, h.uv.x, h.uv.y};
  return true;
}

}  // namespace

bool intersect_block_lane(const TriangleBlock& block, uint32_t lane, uint32_t object, RayQuery& q, HitRecord& hit) {
  const auto vertex = [&](int j) { return Vec3f{block.v[j][0][lane], block.v[j][1][lane], block.v[j][2][lane]}; };
  PrimHit h;
  if (!intersect_triangle(vertex(0), vertex(1), vertex(2), to_ray(q), h)) return false;
  return record(h, object, block.prim[lane], q, hit);
}

bool intersect_analytic(const AnalyticPrim* prims, uint32_t index, RayQuery& q, HitRecord& hit) {
  const AnalyticPrim& prim = prims[index];
  PrimHit h;
  const bool found = std::visit(
      [&](const auto* shape) {
        if constexpr (WholeShape<std::remove_cvref_t<decltype(*shape)>>) {
          return intersect(*shape, to_ray(q), h);
        } else {
          return false;  // never in an analytic leaf (meshes have bottom levels of their own)
        }
      },
      prim.shape);
  return found && record(h, prim.object, 0, q, hit);
}

bool intersect_block_lane_cutout(const TriangleBlock& block, uint32_t lane, uint32_t object, uint32_t instance,
                                 const CutoutTest& cutouts, RayQuery& q, HitRecord& hit) {
  const auto vertex = [&](int j) { return Vec3f{block.v[j][0][lane], block.v[j][1][lane], block.v[j][2][lane]}; };
  const Ray ray = to_ray(q);
  PrimHit h;
  if (!intersect_triangle(vertex(0), vertex(1), vertex(2), ray, h)) return false;
  if (!cutouts.keeps_hit(ray, object, block.prim[lane], h, instance)) return false;
  return record(h, object, block.prim[lane], q, hit);
}

bool intersect_analytic_cutout(const AnalyticPrim* prims, uint32_t index, uint32_t instance,
                               const CutoutTest& cutouts, RayQuery& q, HitRecord& hit) {
  const AnalyticPrim& prim = prims[index];
  PrimHit h;
  const bool found = std::visit(
      [&](const auto* shape) {
        if constexpr (WholeShape<std::remove_cvref_t<decltype(*shape)>>) {
          return intersect_kept(*shape, 0, to_ray(q), h, cutouts, prim.object, instance);
        } else {
          return false;  // never in an analytic leaf
        }
      },
      prim.shape);
  return found && record(h, prim.object, 0, q, hit);
}

bool to_object_space(const Transform& t, const RayQuery& world, RayQuery& local) {
  const Ray r = t.to_object(to_ray(world));
  if (!is_finite(r.origin) || !is_finite(r.dir) || r.dir == Vec3f(0.0f)) return false;
  for (int a = 0; a < 3; ++a) {
    local.org[a] = r.origin[a];
    local.dir[a] = r.dir[a];
  }
  local.tmin = world.tmin;
  local.tmax = world.tmax;
  set_ray_frame(r.dir, local);
  return true;
}

static_assert(kNoInstanceId == kNoInstance);

bool cpu_has_avx2_fma() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

// libgcc reports the AVX-512 features only where XCR0 shows that the OS saves
// the mask and upper vector registers.
bool cpu_has_avx512() {
  return cpu_has_avx2_fma() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
         __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
}

}  // namespace pt::bvh

// Baseline kernel (SSE2, every x86-64): 8-wide nodes tested as two 4-wide
// halves; triangles through the reference routine, lane by lane.
#include <emmintrin.h>

#include "accel/bvh/kernel.h"
#include "accel/bvh/kernels.h"

namespace pt::bvh {

namespace {

class Sse2Ops {
 public:
  explicit Sse2Ops(const RayQuery& q)
      : org_{_mm_set1_ps(q.org[0]), _mm_set1_ps(q.org[1]), _mm_set1_ps(q.org[2])},
        rdir_{_mm_set1_ps(q.rdir[0]), _mm_set1_ps(q.rdir[1]), _mm_set1_ps(q.rdir[2])},
        rdir_far_{_mm_set1_ps(kernel::exit_rdir(q, 0)), _mm_set1_ps(kernel::exit_rdir(q, 1)),
                  _mm_set1_ps(kernel::exit_rdir(q, 2))},
        tmin_(_mm_set1_ps(q.tmin)),
        near_{q.near[0] * 8, q.near[1] * 8, q.near[2] * 8},
        far_{(q.near[0] ^ 1u) * 8, (q.near[1] ^ 1u) * 8, (q.near[2] ^ 1u) * 8} {}

  // Slab test, the bounds as two-level trees: conservative when a distance is
  // NaN (0 * inf, an origin on a slab plane: kernel.h). The wide kernels make
  // exactly these operations (their node counts are compared in the tests).
  uint32_t intersect_node(const Node8& node, float tmax_exit, float* dist) const {
    const __m128 tmax4 = _mm_set1_ps(tmax_exit);
    const float* b = &node.bounds[0][0];
    uint32_t mask = 0;
    for (int h = 0; h < 8; h += 4) {
      const __m128 nx = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + near_[0] + h), org_[0]), rdir_[0]);
      const __m128 ny = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + 16 + near_[1] + h), org_[1]), rdir_[1]);
      const __m128 nz = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + 32 + near_[2] + h), org_[2]), rdir_[2]);
      const __m128 fx = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + far_[0] + h), org_[0]), rdir_far_[0]);
      const __m128 fy = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + 16 + far_[1] + h), org_[1]), rdir_far_[1]);
      const __m128 fz = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + 32 + far_[2] + h), org_[2]), rdir_far_[2]);
      const __m128 tnear = _mm_max_ps(_mm_max_ps(nx, ny), _mm_max_ps(nz, tmin_));
      const __m128 tfar = _mm_min_ps(_mm_min_ps(fx, fy), _mm_min_ps(fz, tmax4));
      _mm_store_ps(dist + h, tnear);
      mask |= static_cast<uint32_t>(_mm_movemask_ps(_mm_cmple_ps(tnear, tfar))) << h;
    }
    return mask;
  }

  template <bool kAnyHit>
  bool intersect_leaf(const TriangleBlock* blocks, uint32_t count, uint32_t object, RayQuery& q,
                      HitRecord& hit) const {
    bool found = false;
    for (uint32_t i = 0; i < count; ++i) {
      for (uint32_t lane = 0; lane < 4; ++lane) {
        if (blocks[i].prim[lane] == kNoPrim) continue;
        if (intersect_block_lane(blocks[i], lane, object, q, hit)) {
          found = true;
          if constexpr (kAnyHit) return true;
        }
      }
    }
    return found;
  }

 private:
  __m128 org_[3], rdir_[3], rdir_far_[3], tmin_;
  uint32_t near_[3], far_[3];  // offsets of the entry / exit rows within an axis' pair of rows
};

bool intersect(const SceneData& s, RayQuery& q, HitRecord& hit) {
  return kernel::traverse_scene<false, false, Sse2Ops>(s, q, hit, nullptr);
}

bool occluded(const SceneData& s, RayQuery& q) {
  HitRecord unused;
  return kernel::traverse_scene<true, false, Sse2Ops>(s, q, unused, nullptr);
}

bool intersect_counted(const SceneData& s, RayQuery& q, HitRecord& hit, Counters& counters) {
  return kernel::traverse_scene<false, true, Sse2Ops>(s, q, hit, &counters);
}

}  // namespace

KernelTable sse2_kernels() { return KernelTable{"SSE2", intersect, occluded, intersect_counted}; }

}  // namespace pt::bvh

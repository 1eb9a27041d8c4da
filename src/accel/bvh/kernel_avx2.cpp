// AVX2 + FMA kernel, compiled with -mavx2 -mfma -ffp-contract=off and called
// only after cpu_has_avx2_fma() (bvh_accel.cpp). Includes nothing but plain
// declarations (layout.h explains why).
//
// Nodes: one 8-wide slab test. Triangles: the watertight test of
// geometry/triangle.cpp on 4 triangles at once, with exactly its operations and
// roundings (the shear as a multiply then an add, the edge functions as the
// FMA difference of products, t, the bound on its error and the barycentrics
// as the same sums, products and divisions), so that each lane's answer is
// bit for bit the reference's. The one case it leaves to the reference routine
// itself: an edge function exactly zero, which the reference re-decides in
// double. -ffp-contract=off keeps the compiler from fusing the multiply-adds
// that the reference rounds twice.
//
// This is a replica: a change to intersect_triangle() must be made here too.
// tests/accel/test_bvh.cpp (KernelsAgreeBitForBit, TriangleFilterMatchesReference)
// fails when the two drift apart.
#include <immintrin.h>

#include "accel/bvh/kernel.h"
#include "accel/bvh/kernels.h"

namespace pt::bvh {

namespace {

// a * b - c * d with Kahan's FMA scheme, as fp::difference_of_products.
inline __m128 difference_of_products(__m128 a, __m128 b, __m128 c, __m128 d) {
  const __m128 cd = _mm_mul_ps(c, d);
  const __m128 err = _mm_fnmadd_ps(c, d, cd);  // fma(-c, d, cd)
  const __m128 dop = _mm_fmsub_ps(a, b, cd);   // fma(a, b, -cd)
  return _mm_add_ps(dop, err);
}

// |x| per lane, and the largest of |a|, |b|, |c| per lane.
inline __m128 abs4(__m128 x) { return _mm_and_ps(x, _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff))); }
inline __m128 max_abs3(__m128 a, __m128 b, __m128 c) { return _mm_max_ps(_mm_max_ps(abs4(a), abs4(b)), abs4(c)); }

// The reference's bound on the error of t (geometry/triangle.cpp: delta_t),
// from the lanes' largest |x|, |y|, |z| (before the scaling by sz) and |z sz|
// of the sheared vertices, largest |e| and |det|.
inline __m128 t_error_bound(__m128 max_xt, __m128 max_yt, __m128 max_z, __m128 max_zt, __m128 max_e,
                            __m128 abs_det) {
  const __m128 g2 = _mm_set1_ps(kGamma2), g3 = _mm_set1_ps(kGamma3), g5 = _mm_set1_ps(kGamma5);
  const __m128 delta_z = _mm_mul_ps(g3, max_zt);
  const __m128 delta_x = _mm_mul_ps(g5, _mm_add_ps(max_xt, max_z));
  const __m128 delta_y = _mm_mul_ps(g5, _mm_add_ps(max_yt, max_z));
  const __m128 delta_e = _mm_mul_ps(
      _mm_set1_ps(2.0f), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(g2, max_xt), max_yt), _mm_mul_ps(delta_y, max_xt)),
                                    _mm_mul_ps(delta_x, max_yt)));
  return _mm_div_ps(_mm_mul_ps(_mm_set1_ps(3.0f), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(g3, max_e), max_zt),
                                                                        _mm_mul_ps(delta_e, max_zt)),
                                                             _mm_mul_ps(delta_z, max_e))),
                    abs_det);
}

// Records the nearest of the hit lanes (the lowest one on a tie, as if the
// lanes were tested one after the other).
inline void nearest_lane(uint32_t hits, __m128 t, __m128 e1, __m128 e2, __m128 det, const uint32_t* prim,
                         uint32_t object, RayQuery& q, HitRecord& hit) {
  alignas(16) float tl[4], e1l[4], e2l[4], detl[4];
  _mm_store_ps(tl, t);
  _mm_store_ps(e1l, e1);
  _mm_store_ps(e2l, e2);
  _mm_store_ps(detl, det);
  uint32_t best = static_cast<uint32_t>(__builtin_ctz(hits));
  for (uint32_t rest = hits & (hits - 1); rest != 0; rest &= rest - 1) {
    const uint32_t lane = static_cast<uint32_t>(__builtin_ctz(rest));
    if (tl[lane] < tl[best]) best = lane;
  }
  q.tmax = tl[best];
  hit = HitRecord{tl[best], object, prim[best], e1l[best] / detl[best], e2l[best] / detl[best]};
}

class Avx2Ops {
 public:
  explicit Avx2Ops(const RayQuery& q)
      : org_{_mm256_set1_ps(q.org[0]), _mm256_set1_ps(q.org[1]), _mm256_set1_ps(q.org[2])},
        rdir_{_mm256_set1_ps(q.rdir[0]), _mm256_set1_ps(q.rdir[1]), _mm256_set1_ps(q.rdir[2])},
        tmin_(_mm256_set1_ps(q.tmin)),
        near_{q.near[0] * 8, q.near[1] * 8, q.near[2] * 8},
        far_{(q.near[0] ^ 1u) * 8, (q.near[1] ^ 1u) * 8, (q.near[2] ^ 1u) * 8},
        korg_{_mm_set1_ps(q.org[q.kx]), _mm_set1_ps(q.org[q.ky]), _mm_set1_ps(q.org[q.kz])},
        shear_{_mm_set1_ps(q.sx), _mm_set1_ps(q.sy), _mm_set1_ps(q.sz)},
        tmin4_(_mm_set1_ps(q.tmin)),
        row_{q.kx * 4, q.ky * 4, q.kz * 4} {}

  // Slab test; see kernel_sse2.cpp for the NaN rule (max/min keep their
  // second operand, the running bound, when the first is NaN).
  uint32_t intersect_node(const Node8& node, float tmax, float* dist) const {
    const float* b = &node.bounds[0][0];
    const __m256 nx = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + near_[0]), org_[0]), rdir_[0]);
    const __m256 ny = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + 16 + near_[1]), org_[1]), rdir_[1]);
    const __m256 nz = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + 32 + near_[2]), org_[2]), rdir_[2]);
    const __m256 fx = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + far_[0]), org_[0]), rdir_[0]);
    const __m256 fy = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + 16 + far_[1]), org_[1]), rdir_[1]);
    const __m256 fz = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + 32 + far_[2]), org_[2]), rdir_[2]);
    const __m256 tnear = _mm256_max_ps(nx, _mm256_max_ps(ny, _mm256_max_ps(nz, tmin_)));
    const __m256 tfar = _mm256_mul_ps(_mm256_min_ps(fx, _mm256_min_ps(fy, _mm256_min_ps(fz, _mm256_set1_ps(tmax)))),
                                      _mm256_set1_ps(kernel::kExitScale));
    _mm256_store_ps(dist, tnear);
    return static_cast<uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(tnear, tfar, _CMP_LE_OQ)));
  }

  template <bool kAnyHit>
  bool intersect_block(const TriangleBlock& block, uint32_t object, RayQuery& q, HitRecord& hit) const {
    const float* v = &block.v[0][0][0];  // vertex j, axis k: v + 12 j + 4 k
    // Translate to the ray origin in the permuted frame, then shear.
    __m128 ax = _mm_sub_ps(_mm_load_ps(v + row_[0]), korg_[0]);
    __m128 ay = _mm_sub_ps(_mm_load_ps(v + row_[1]), korg_[1]);
    const __m128 az = _mm_sub_ps(_mm_load_ps(v + row_[2]), korg_[2]);
    __m128 bx = _mm_sub_ps(_mm_load_ps(v + 12 + row_[0]), korg_[0]);
    __m128 by = _mm_sub_ps(_mm_load_ps(v + 12 + row_[1]), korg_[1]);
    const __m128 bz = _mm_sub_ps(_mm_load_ps(v + 12 + row_[2]), korg_[2]);
    __m128 cx = _mm_sub_ps(_mm_load_ps(v + 24 + row_[0]), korg_[0]);
    __m128 cy = _mm_sub_ps(_mm_load_ps(v + 24 + row_[1]), korg_[1]);
    const __m128 cz = _mm_sub_ps(_mm_load_ps(v + 24 + row_[2]), korg_[2]);
    ax = _mm_add_ps(ax, _mm_mul_ps(shear_[0], az));
    ay = _mm_add_ps(ay, _mm_mul_ps(shear_[1], az));
    bx = _mm_add_ps(bx, _mm_mul_ps(shear_[0], bz));
    by = _mm_add_ps(by, _mm_mul_ps(shear_[1], bz));
    cx = _mm_add_ps(cx, _mm_mul_ps(shear_[0], cz));
    cy = _mm_add_ps(cy, _mm_mul_ps(shear_[1], cz));

    const __m128 e0 = difference_of_products(bx, cy, by, cx);
    const __m128 e1 = difference_of_products(cx, ay, cy, ax);
    const __m128 e2 = difference_of_products(ax, by, ay, bx);
    const __m128 zero = _mm_setzero_ps();
    const __m128 any_zero =
        _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(e0, zero), _mm_cmpeq_ps(e1, zero)), _mm_cmpeq_ps(e2, zero));
    const __m128 any_neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(e0, zero), _mm_cmplt_ps(e1, zero)), _mm_cmplt_ps(e2, zero));
    const __m128 any_pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(e0, zero), _mm_cmpgt_ps(e1, zero)), _mm_cmpgt_ps(e2, zero));
    const __m128 det = _mm_add_ps(_mm_add_ps(e0, e1), e2);
    const __m128 t_num = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e0, _mm_mul_ps(az, shear_[2])),
                                               _mm_mul_ps(e1, _mm_mul_ps(bz, shear_[2]))),
                                    _mm_mul_ps(e2, _mm_mul_ps(cz, shear_[2])));
    const __m128 t = _mm_div_ps(t_num, det);
    const __m128 in_range = _mm_and_ps(_mm_cmpgt_ps(t, tmin4_), _mm_cmplt_ps(t, _mm_set1_ps(q.tmax)));
    const __m128 inside = _mm_andnot_ps(_mm_and_ps(any_neg, any_pos), _mm_and_ps(_mm_cmpneq_ps(det, zero), in_range));
    if (_mm_movemask_ps(_mm_or_ps(any_zero, inside)) == 0) return false;

    // The reference's rejection of t that is not conservatively positive,
    // operation for operation (it removes the surface a ray starts on),
    // waived, as there, for a triangle entirely ahead of the origin.
    const __m128 azs = _mm_mul_ps(az, shear_[2]), bzs = _mm_mul_ps(bz, shear_[2]), czs = _mm_mul_ps(cz, shear_[2]);
    const __m128 certainly_ahead =
        _mm_and_ps(_mm_and_ps(_mm_cmpgt_ps(azs, zero), _mm_cmpgt_ps(bzs, zero)), _mm_cmpgt_ps(czs, zero));
    const __m128 delta_t = t_error_bound(max_abs3(ax, bx, cx), max_abs3(ay, by, cy), max_abs3(az, bz, cz),
                                         max_abs3(azs, bzs, czs), max_abs3(e0, e1, e2), abs4(det));
    const uint32_t zero_lanes = static_cast<uint32_t>(_mm_movemask_ps(any_zero));
    const uint32_t hits = static_cast<uint32_t>(
        _mm_movemask_ps(_mm_and_ps(inside, _mm_or_ps(_mm_cmpgt_ps(t, delta_t), certainly_ahead))));
    if (zero_lanes == 0) {
      // Every test of the reference has been made, with its results (degenerate
      // triangles, its last test, have NaN vertices in the blocks and never get
      // here). The nearest lane wins, the lowest one on a tie, as if the lanes
      // were tested one after the other.
      if (hits == 0) return false;
      if constexpr (kAnyHit) {
        return true;
      } else {
        nearest_lane(hits, t, e1, e2, det, block.prim, object, q, hit);
        return true;
      }
    }
    // An edge function exactly zero: the reference decides those lanes in
    // double. Test every candidate lane with it, in order.
    bool found = false;
    for (uint32_t candidates = zero_lanes | hits; candidates != 0; candidates &= candidates - 1) {
      if (intersect_block_lane(block, static_cast<uint32_t>(__builtin_ctz(candidates)), object, q, hit)) {
        found = true;
        if constexpr (kAnyHit) return true;
      }
    }
    return found;
  }

 private:
  __m256 org_[3], rdir_[3], tmin_;
  uint32_t near_[3], far_[3];
  __m128 korg_[3], shear_[3], tmin4_;
  uint32_t row_[3];
};

bool intersect(const SceneData& s, RayQuery& q, HitRecord& hit) {
  return kernel::traverse_scene<false, false, Avx2Ops>(s, q, hit, nullptr);
}

bool occluded(const SceneData& s, RayQuery& q) {
  HitRecord unused;
  return kernel::traverse_scene<true, false, Avx2Ops>(s, q, unused, nullptr);
}

bool intersect_counted(const SceneData& s, RayQuery& q, HitRecord& hit, Counters& counters) {
  return kernel::traverse_scene<false, true, Avx2Ops>(s, q, hit, &counters);
}

}  // namespace

KernelTable avx2_kernels() { return KernelTable{"AVX2", intersect, occluded, intersect_counted}; }

}  // namespace pt::bvh

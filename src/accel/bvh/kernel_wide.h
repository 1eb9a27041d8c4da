// The wide kernel's body: included by kernel_avx2.cpp (compiled with -mavx2
// -mfma -ffp-contract=off) and kernel_avx512.cpp (the same plus AVX-512 F, VL,
// DQ and BW: 32 vector registers and mask registers for the same 8-lane
// code), each called only after its run-time check (bvh_accel.cpp). Everything
// here lives in an anonymous namespace, so each including file gets copies of
// its own, compiled for its instruction set. Includes nothing but plain
// declarations (layout.h explains why).
//
// Nodes: one 8-wide slab test. Triangles: the watertight test of
// geometry/triangle.cpp on a leaf's blocks, 8 triangles (two blocks) at once,
// a last odd block on 4 lanes, with exactly its operations and
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
#pragma once

#include <immintrin.h>

#include "accel/bvh/kernel.h"
#include "accel/bvh/kernels.h"

namespace pt::bvh {

namespace {

// The operations of the triangle test, for 4 lanes (one block) and 8 lanes
// (two blocks at once): one body (BlockTest below) serves both widths.
inline __m128 add(__m128 a, __m128 b) { return _mm_add_ps(a, b); }
inline __m256 add(__m256 a, __m256 b) { return _mm256_add_ps(a, b); }
inline __m128 sub(__m128 a, __m128 b) { return _mm_sub_ps(a, b); }
inline __m256 sub(__m256 a, __m256 b) { return _mm256_sub_ps(a, b); }
inline __m128 mul(__m128 a, __m128 b) { return _mm_mul_ps(a, b); }
inline __m256 mul(__m256 a, __m256 b) { return _mm256_mul_ps(a, b); }
inline __m128 div(__m128 a, __m128 b) { return _mm_div_ps(a, b); }
inline __m256 div(__m256 a, __m256 b) { return _mm256_div_ps(a, b); }
inline __m128 vmax(__m128 a, __m128 b) { return _mm_max_ps(a, b); }
inline __m256 vmax(__m256 a, __m256 b) { return _mm256_max_ps(a, b); }
inline __m128 fnmadd(__m128 a, __m128 b, __m128 c) { return _mm_fnmadd_ps(a, b, c); }
inline __m256 fnmadd(__m256 a, __m256 b, __m256 c) { return _mm256_fnmadd_ps(a, b, c); }
inline __m128 fmsub(__m128 a, __m128 b, __m128 c) { return _mm_fmsub_ps(a, b, c); }
inline __m256 fmsub(__m256 a, __m256 b, __m256 c) { return _mm256_fmsub_ps(a, b, c); }
inline __m128 vand(__m128 a, __m128 b) { return _mm_and_ps(a, b); }
inline __m256 vand(__m256 a, __m256 b) { return _mm256_and_ps(a, b); }
inline __m128 vor(__m128 a, __m128 b) { return _mm_or_ps(a, b); }
inline __m256 vor(__m256 a, __m256 b) { return _mm256_or_ps(a, b); }
inline __m128 andnot(__m128 a, __m128 b) { return _mm_andnot_ps(a, b); }
inline __m256 andnot(__m256 a, __m256 b) { return _mm256_andnot_ps(a, b); }
inline __m128 eq(__m128 a, __m128 b) { return _mm_cmpeq_ps(a, b); }
inline __m256 eq(__m256 a, __m256 b) { return _mm256_cmp_ps(a, b, _CMP_EQ_OQ); }
inline __m128 neq(__m128 a, __m128 b) { return _mm_cmpneq_ps(a, b); }
inline __m256 neq(__m256 a, __m256 b) { return _mm256_cmp_ps(a, b, _CMP_NEQ_UQ); }
inline __m128 lt(__m128 a, __m128 b) { return _mm_cmplt_ps(a, b); }
inline __m256 lt(__m256 a, __m256 b) { return _mm256_cmp_ps(a, b, _CMP_LT_OS); }
inline __m128 gt(__m128 a, __m128 b) { return _mm_cmpgt_ps(a, b); }
inline __m256 gt(__m256 a, __m256 b) { return _mm256_cmp_ps(a, b, _CMP_GT_OS); }
inline uint32_t movemask(__m128 a) { return static_cast<uint32_t>(_mm_movemask_ps(a)); }
inline uint32_t movemask(__m256 a) { return static_cast<uint32_t>(_mm256_movemask_ps(a)); }
inline void store(float* p, __m128 a) { _mm_storeu_ps(p, a); }
inline void store(float* p, __m256 a) { _mm256_storeu_ps(p, a); }
template <class V>
inline V splat(float x);
template <>
inline __m128 splat<__m128>(float x) { return _mm_set1_ps(x); }
template <>
inline __m256 splat<__m256>(float x) { return _mm256_set1_ps(x); }

// Row `offset` (floats from the start of a block) of the lanes under test:
// one block's 4 lanes, or two blocks' 8 (the first block in the low half).
inline __m128 load_row(const TriangleBlock* b, uint32_t offset, __m128) {
  return _mm_load_ps(&b[0].v[0][0][0] + offset);
}
inline __m256 load_row(const TriangleBlock* b, uint32_t offset, __m256) {
  return _mm256_set_m128(_mm_load_ps(&b[1].v[0][0][0] + offset), _mm_load_ps(&b[0].v[0][0][0] + offset));
}

// a * b - c * d with Kahan's FMA scheme, as fp::difference_of_products.
template <class V>
inline V difference_of_products(V a, V b, V c, V d) {
  const V cd = mul(c, d);
  const V err = fnmadd(c, d, cd);  // fma(-c, d, cd)
  const V dop = fmsub(a, b, cd);   // fma(a, b, -cd)
  return add(dop, err);
}

// |x| per lane, and the largest of |a|, |b|, |c| per lane.
template <class V>
inline V abs_v(V x) { return andnot(splat<V>(-0.0f), x); }
template <class V>
inline V max_abs3(V a, V b, V c) { return vmax(vmax(abs_v(a), abs_v(b)), abs_v(c)); }

// The reference's bound on the error of t (geometry/triangle.cpp: delta_t),
// from the lanes' largest |x|, |y|, |z| (before the scaling by sz) and |z sz|
// of the sheared vertices, largest |e| and |det|.
template <class V>
inline V t_error_bound(V max_xt, V max_yt, V max_z, V max_zt, V max_e, V abs_det) {
  const V g2 = splat<V>(kGamma2), g3 = splat<V>(kGamma3), g5 = splat<V>(kGamma5);
  const V delta_z = mul(g3, max_zt);
  const V delta_x = mul(g5, add(max_xt, max_z));
  const V delta_y = mul(g5, add(max_yt, max_z));
  const V delta_e = mul(splat<V>(2.0f), add(add(mul(mul(g2, max_xt), max_yt), mul(delta_y, max_xt)), mul(delta_x, max_yt)));
  return div(mul(splat<V>(3.0f), add(add(mul(mul(g3, max_e), max_zt), mul(delta_e, max_zt)), mul(delta_z, max_e))),
             abs_det);
}

// The ray's constants for the triangle test, broadcast to a width (4 or 8
// lanes; a width, not the vector type, as the template argument: GCC drops a
// vector type's attributes there).
template <int kWidth>
struct Lanes;
template <>
struct Lanes<4> {
  using type = __m128;
};
template <>
struct Lanes<8> {
  using type = __m256;
};
template <int kWidth>
struct TriangleRay {
  using V = typename Lanes<kWidth>::type;
  V korg[3], shear[3], tmin;
  uint32_t row[3];  // offsets of the permuted axes' rows within a vertex
  explicit TriangleRay(const RayQuery& q)
      : korg{splat<V>(q.org[q.kx]), splat<V>(q.org[q.ky]), splat<V>(q.org[q.kz])},
        shear{splat<V>(q.sx), splat<V>(q.sy), splat<V>(q.sz)},
        tmin(splat<V>(q.tmin)),
        row{q.kx * 4, q.ky * 4, q.kz * 4} {}
  // The 4-lane constants as the low halves of the 8-lane ones (no broadcast
  // per ray for the odd block of a leaf).
  explicit TriangleRay(const TriangleRay<8>& r)
      : korg{_mm256_castps256_ps128(r.korg[0]), _mm256_castps256_ps128(r.korg[1]),
             _mm256_castps256_ps128(r.korg[2])},
        shear{_mm256_castps256_ps128(r.shear[0]), _mm256_castps256_ps128(r.shear[1]),
              _mm256_castps256_ps128(r.shear[2])},
        tmin(_mm256_castps256_ps128(r.tmin)),
        row{r.row[0], r.row[1], r.row[2]} {}
};

// Records the nearest of the hit lanes (the lowest one on a tie, as if the
// lanes were tested one after the other); lane l is lane l % 4 of block l / 4.
template <class V>
inline void nearest_lane(uint32_t hits, V t, V e1, V e2, V det, const TriangleBlock* blocks, uint32_t object,
                         RayQuery& q, HitRecord& hit) {
  float tl[8], e1l[8], e2l[8], detl[8];
  store(tl, t);
  store(e1l, e1);
  store(e2l, e2);
  store(detl, det);
  uint32_t best = static_cast<uint32_t>(__builtin_ctz(hits));
  for (uint32_t rest = hits & (hits - 1); rest != 0; rest &= rest - 1) {
    const uint32_t lane = static_cast<uint32_t>(__builtin_ctz(rest));
    if (tl[lane] < tl[best]) best = lane;
  }
  q.tmax = tl[best];
  hit = HitRecord{tl[best], object, blocks[best / 4].prim[best % 4], e1l[best] / detl[best], e2l[best] / detl[best]};
}

// The watertight test on the lanes of one block (V = __m128) or two (__m256).
template <bool kAnyHit, int kWidth>
bool intersect_blocks(const TriangleRay<kWidth>& r, const TriangleBlock* blocks, uint32_t object, RayQuery& q,
                      HitRecord& hit) {
  using V = typename TriangleRay<kWidth>::V;
  // Vertex j, axis k: row 12 j + 4 k. Translate to the ray origin in the
  // permuted frame, then shear.
  V ax = sub(load_row(blocks, r.row[0], V{}), r.korg[0]);
  V ay = sub(load_row(blocks, r.row[1], V{}), r.korg[1]);
  const V az = sub(load_row(blocks, r.row[2], V{}), r.korg[2]);
  V bx = sub(load_row(blocks, 12 + r.row[0], V{}), r.korg[0]);
  V by = sub(load_row(blocks, 12 + r.row[1], V{}), r.korg[1]);
  const V bz = sub(load_row(blocks, 12 + r.row[2], V{}), r.korg[2]);
  V cx = sub(load_row(blocks, 24 + r.row[0], V{}), r.korg[0]);
  V cy = sub(load_row(blocks, 24 + r.row[1], V{}), r.korg[1]);
  const V cz = sub(load_row(blocks, 24 + r.row[2], V{}), r.korg[2]);
  ax = add(ax, mul(r.shear[0], az));
  ay = add(ay, mul(r.shear[1], az));
  bx = add(bx, mul(r.shear[0], bz));
  by = add(by, mul(r.shear[1], bz));
  cx = add(cx, mul(r.shear[0], cz));
  cy = add(cy, mul(r.shear[1], cz));

  const V e0 = difference_of_products(bx, cy, by, cx);
  const V e1 = difference_of_products(cx, ay, cy, ax);
  const V e2 = difference_of_products(ax, by, ay, bx);
  const V zero = splat<V>(0.0f);
  const V any_zero = vor(vor(eq(e0, zero), eq(e1, zero)), eq(e2, zero));
  const V any_neg = vor(vor(lt(e0, zero), lt(e1, zero)), lt(e2, zero));
  const V any_pos = vor(vor(gt(e0, zero), gt(e1, zero)), gt(e2, zero));
  const V det = add(add(e0, e1), e2);
  const V azs = mul(az, r.shear[2]), bzs = mul(bz, r.shear[2]), czs = mul(cz, r.shear[2]);
  const V t_num = add(add(mul(e0, azs), mul(e1, bzs)), mul(e2, czs));
  const V t = div(t_num, det);
  const V in_range = vand(gt(t, r.tmin), lt(t, splat<V>(q.tmax)));
  const V inside = andnot(vand(any_neg, any_pos), vand(neq(det, zero), in_range));
  if (movemask(vor(any_zero, inside)) == 0) return false;

  // The reference's rejection of t that is not conservatively positive,
  // operation for operation (it removes the surface a ray starts on),
  // waived, as there, for a triangle entirely ahead of the origin.
  const V certainly_ahead = vand(vand(gt(azs, zero), gt(bzs, zero)), gt(czs, zero));
  const V delta_t = t_error_bound(max_abs3(ax, bx, cx), max_abs3(ay, by, cy), max_abs3(az, bz, cz),
                                  max_abs3(azs, bzs, czs), max_abs3(e0, e1, e2), abs_v(det));
  const uint32_t zero_lanes = movemask(any_zero);
  const uint32_t hits = movemask(vand(inside, vor(gt(t, delta_t), certainly_ahead)));
  if (zero_lanes == 0) {
    // Every test of the reference has been made, with its results (degenerate
    // triangles, its last test, have NaN vertices in the blocks and never get
    // here). The nearest lane wins, the lowest one on a tie, as if the lanes
    // were tested one after the other.
    if (hits == 0) return false;
    if constexpr (!kAnyHit) nearest_lane(hits, t, e1, e2, det, blocks, object, q, hit);
    return true;
  }
  // An edge function exactly zero: the reference decides those lanes in
  // double. Test every candidate lane with it, in order.
  bool found = false;
  for (uint32_t candidates = zero_lanes | hits; candidates != 0; candidates &= candidates - 1) {
    const auto lane = static_cast<uint32_t>(__builtin_ctz(candidates));
    if (intersect_block_lane(blocks[lane / 4], lane % 4, object, q, hit)) {
      found = true;
      if constexpr (kAnyHit) return true;
    }
  }
  return found;
}

class Avx2Ops {
 public:
  explicit Avx2Ops(const RayQuery& q)
      : org_{_mm256_set1_ps(q.org[0]), _mm256_set1_ps(q.org[1]), _mm256_set1_ps(q.org[2])},
        rdir_{_mm256_set1_ps(q.rdir[0]), _mm256_set1_ps(q.rdir[1]), _mm256_set1_ps(q.rdir[2])},
        rdir_far_{_mm256_set1_ps(kernel::exit_rdir(q, 0)), _mm256_set1_ps(kernel::exit_rdir(q, 1)),
                  _mm256_set1_ps(kernel::exit_rdir(q, 2))},
        tmin_(_mm256_set1_ps(q.tmin)),
        near_{q.near[0] * 8, q.near[1] * 8, q.near[2] * 8},
        far_{(q.near[0] ^ 1u) * 8, (q.near[1] ^ 1u) * 8, (q.near[2] ^ 1u) * 8},
        tri8_(q) {}

  // Slab test; see kernel.h (exit_rdir, and why the two-level trees of the
  // bounds are conservative when a distance is NaN). Exits are widened through
  // rdir_far_ and tmax_exit (tmax * kExitScale), so no multiply follows the
  // minimum. AVX-512: the compare straight into a mask register.
  uint32_t intersect_node(const Node8& node, float tmax_exit, float* dist) const {
    const float* b = &node.bounds[0][0];
    const __m256 nx = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + near_[0]), org_[0]), rdir_[0]);
    const __m256 ny = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + 16 + near_[1]), org_[1]), rdir_[1]);
    const __m256 nz = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + 32 + near_[2]), org_[2]), rdir_[2]);
    const __m256 fx = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + far_[0]), org_[0]), rdir_far_[0]);
    const __m256 fy = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + 16 + far_[1]), org_[1]), rdir_far_[1]);
    const __m256 fz = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b + 32 + far_[2]), org_[2]), rdir_far_[2]);
    const __m256 tmax8 = _mm256_set1_ps(tmax_exit);
    const __m256 tnear = _mm256_max_ps(_mm256_max_ps(nx, ny), _mm256_max_ps(nz, tmin_));
    const __m256 tfar = _mm256_min_ps(_mm256_min_ps(fx, fy), _mm256_min_ps(fz, tmax8));
    _mm256_store_ps(dist, tnear);
#ifdef __AVX512VL__
    return static_cast<uint32_t>(_mm256_cmp_ps_mask(tnear, tfar, _CMP_LE_OQ));
#else
    return static_cast<uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(tnear, tfar, _CMP_LE_OQ)));
#endif
  }

  // A leaf's blocks, two at a time (8 lanes), then the last one alone.
  template <bool kAnyHit>
  bool intersect_leaf(const TriangleBlock* blocks, uint32_t count, uint32_t object, RayQuery& q,
                      HitRecord& hit) const {
    bool found = false;
    uint32_t i = 0;
    for (; i + 1 < count; i += 2) {
      if (intersect_blocks<kAnyHit>(tri8_, blocks + i, object, q, hit)) {
        found = true;
        if constexpr (kAnyHit) return true;
      }
    }
    if (i < count && intersect_blocks<kAnyHit>(TriangleRay<4>(tri8_), blocks + i, object, q, hit)) found = true;
    return found;
  }

 private:
  __m256 org_[3], rdir_[3], rdir_far_[3], tmin_;
  uint32_t near_[3], far_[3];
  TriangleRay<8> tri8_;
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

}  // namespace pt::bvh

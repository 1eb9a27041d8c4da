// The traversal layout of the BVH: plain data shared by the builders
// (blas.cpp, bvh_accel.cpp) and the traversal kernels (kernel_*.cpp).
//
// This header deliberately holds only plain structs, constants and function
// declarations, and includes nothing but <cstdint>: kernel_avx2.cpp is compiled
// with -mavx2 -mfma, and an inline function it pulled in from a shared header
// could be emitted there with AVX2 instructions and then chosen by the linker
// for callers on CPUs without AVX2. The kernels call out-of-line functions
// (compiled for the baseline ISA) for everything outside their own file.
#pragma once

#include <cstdint>

namespace pt {
struct Transform;   // core/transform.h; the kernels only pass it on (to_object_space)
struct CutoutTest;  // accel/cutout.h; the kernels only pass it on (the *_cutout leaf routines)
}

namespace pt::bvh {

// ---------------------------------------------------------------- references
// A child reference is a node index (bit 31 clear) or a leaf (bit 31 set):
// bits 0-26 the first item (triangle block, analytic primitive or, in the top
// level, bottom-level BVH), bits 27-30 the item count minus one.
inline constexpr uint32_t kLeafBit = 0x80000000u;
inline constexpr uint32_t kLeafCountShift = 27;
inline constexpr uint32_t kLeafIndexMask = (1u << kLeafCountShift) - 1;
inline constexpr uint32_t kMaxLeafItems = 16;
inline constexpr uint32_t kMaxItems = kLeafIndexMask + 1;
// Unused child slots: never reached (their box is empty), but well defined.
inline constexpr uint32_t kEmptyRef = kLeafBit;

// ---------------------------------------------------------------- nodes
// An 8-wide node, bounds in SoA rows: rows 2a and 2a + 1 hold the lower and
// upper bounds of axis a for the 8 children. Empty slots have lo = +inf,
// hi = -inf, which no ray hits. The child references come first, so that they
// share a cache line with the first row of bounds (half the nodes) or lie in
// the line before it, fetched with the bounds rather than after the test.
struct alignas(32) Node8 {
  uint32_t child[8];
  float bounds[6][8];
};
static_assert(sizeof(Node8) == 224);

// ---------------------------------------------------------------- leaves
// Four triangles in SoA: v[vertex][axis][lane], exact copies of the mesh's
// vertex positions. Unused lanes have NaN vertices (never hit) and kNoPrim;
// exactly degenerate triangles, which the reference test never reports, have
// NaN vertices and their triangle index.
inline constexpr uint32_t kNoPrim = 0xFFFFFFFFu;
struct alignas(16) TriangleBlock {
  float v[3][3][4];
  uint32_t prim[4];
};
static_assert(sizeof(TriangleBlock) == 160);

// An analytic shape in a bottom-level leaf (bvh/analytic.h: a typed reference
// to the shape, generated from the Shape variant; declared only, as the
// kernels merely pass the leaf's array and index on to intersect_analytic()).
struct AnalyticPrim;

enum class BlasKind : uint16_t { Triangles, Analytic };

// The instance id of a hit on a shape placed directly (geometry's kNoInstance).
inline constexpr uint32_t kNoInstanceId = 0xFFFFFFFFu;

// One bottom-level BVH as the kernels see it: placed directly (transform
// nullptr, instance kNoInstanceId), or one placement of it (an instance of a
// prototype: the ray goes to object space, the BVH is shared).
struct BlasData {
  const Node8* nodes;
  uint32_t root;                 // a node or a leaf reference
  BlasKind kind;
  uint16_t cutout;               // nonzero: a shape of it may be cut out in this placement (SceneData::cutouts)
  const TriangleBlock* blocks;   // Triangles
  const AnalyticPrim* prims;     // Analytic
  uint32_t object;               // Triangles: the mesh's object id
  uint32_t instance;             // the instance id, or kNoInstanceId
  const Transform* transform;    // object to world, or nullptr when placed directly
};
static_assert(sizeof(BlasData) == 48);

// The whole scene: a top-level BVH whose leaves are bottom-level BVHs. With a
// single bottom-level BVH placed directly the top level is skipped.
struct SceneData {
  const Node8* nodes;
  uint32_t root;
  const BlasData* blas;
  uint32_t blas_count;
  // Nonzero when the items need the general loop: some are placed by
  // instances (a transform to test) or some may be cut out. 0: the loop of a
  // scene of shapes placed directly, as before either existed.
  uint32_t general;
  const CutoutTest* cutouts;  // the scene's cutout test; null if nothing is cut out
};

// ---------------------------------------------------------------- rays
// A ray prepared for traversal (bvh_accel.cpp: prepare_ray). The interval
// (tmin, tmax) is open; tmax shrinks as closer hits are found.
struct RayQuery {
  float org[3];
  float dir[3];
  float rdir[3];      // 1 / dir (+-inf for a zero component, with its sign)
  float tmin;
  float tmax;
  uint32_t near[3];   // entry plane of axis a: row 2a + near[a] of Node8::bounds (1 iff dir[a] has its sign bit set)
  // The watertight triangle test's ray frame (geometry/triangle.cpp): axis
  // permutation with the dominant direction last, and the shear constants.
  uint32_t kx, ky, kz;
  float sx, sy, sz;
};

struct HitRecord {
  float t;
  uint32_t object;
  uint32_t prim;
  float u, v;
  uint32_t instance = kNoInstanceId;  // set by the top level for a hit through an instance
};

struct Counters {
  uint32_t nodes;  // nodes whose children were tested
  uint32_t prims;  // primitives tested (occupied lanes of triangle blocks, analytic shapes)
};

// ---------------------------------------------------------------- leaf routines (baseline ISA)
// The reference tests, in leaf_tests.cpp: they call src/geometry and are the
// semantic authority; a SIMD kernel only ever filters candidates for them.
// Each updates `hit` and q.tmax on a hit with q.tmin < t < q.tmax.
bool intersect_block_lane(const TriangleBlock& block, uint32_t lane, uint32_t object, RayQuery& q, HitRecord& hit);
bool intersect_analytic(const AnalyticPrim* prims, uint32_t index, RayQuery& q, HitRecord& hit);
// The same for a leaf of a bottom level that may be cut out (placed by
// `instance`, kNoInstanceId if directly): a candidate counts only if the
// cutout test keeps it (accel/cutout.h); past a dropped one the shape's next
// hit along the ray is tried.
bool intersect_block_lane_cutout(const TriangleBlock& block, uint32_t lane, uint32_t object, uint32_t instance,
                                 const CutoutTest& cutouts, RayQuery& q, HitRecord& hit);
bool intersect_analytic_cutout(const AnalyticPrim* prims, uint32_t index, uint32_t instance,
                               const CutoutTest& cutouts, RayQuery& q, HitRecord& hit);
// The world query `world` in the object space of `t` (same t parameter and
// interval, the direction not renormalised), prepared as bvh_accel.cpp's
// prepare() prepares a ray. False if the ray cannot hit anything there.
bool to_object_space(const Transform& t, const RayQuery& world, RayQuery& local);

}  // namespace pt::bvh

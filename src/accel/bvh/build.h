// The wide-BVH builder: binned SAH (Wald 2007) over primitive boxes only.
//
// The builder sees nothing but a box per primitive (and the centre it derives
// from it); what a primitive is, and how leaves are stored, is decided by the
// caller (blas.cpp turns a BuildTree into the traversal layout). Nodes have up
// to kWidth children: a node is filled by repeatedly splitting, with a binned
// SAH split, the child of largest surface area until it has kWidth children or
// no child is worth splitting (the scheme of Embree's BVH-N builders).
//
// Determinism: the tree depends only on the input and the settings, never on
// the thread count or the scheduling. Binning reduces with min/max and integer
// sums (exact, so associative), partitions are in place within disjoint ranges,
// and the nodes are numbered afterwards in depth-first order (blas.cpp).
//
// Call build_tree() inside WorkerPool::run: large ranges are binned and built
// in parallel with TBB.
#pragma once

#include <cstdint>
#include <vector>

#include <tbb/concurrent_vector.h>

#include "core/math.h"

namespace pt::bvh {

inline constexpr int kWidth = 8;  // children per node

// Deepest node level the builder produces (the root is level 0). Below
// kMedianDepth every split halves its range (object median), so the depth is
// bounded whatever the input; traversal stacks are sized from kMaxDepth.
inline constexpr int kMedianDepth = 40;
inline constexpr int kMaxDepth = 64;

// A primitive as the builder sees it: its conservative bounds and the
// caller's index, laid out as two 16-byte rows for SIMD loads.
struct alignas(16) PrimRef {
  Vec3f lo;
  uint32_t id = 0;
  Vec3f hi;
  uint32_t unused = 0;

  PrimRef() = default;
  PrimRef(const Bounds3f& box, uint32_t id_) : lo(box.lo), id(id_), hi(box.hi) {}
  Bounds3f box() const { return Bounds3f{lo, hi}; }
};
static_assert(sizeof(PrimRef) == 32);

struct BuildSettings {
  int bins = 16;               // SAH bins per axis, 4 to 32
  int max_leaf_size = 8;       // primitives per leaf, 1 to 16
  int leaf_block = 4;          // leaf cost counts blocks of this many primitives (SIMD leaves)
  float node_cost = 1.0f;      // SAH cost of one more binary split (a share of a wide-node test)
  float block_cost = 1.0f;     // SAH cost of intersecting one leaf block
  std::size_t parallel_threshold = 2048;  // ranges larger than this are built by parallel tasks
};

// A reference to a child: a node index, or a leaf (kLeafRef set) indexing BuildTree::leaves.
inline constexpr uint32_t kLeafRef = 0x80000000u;

struct BuildNode {
  Bounds3f box[kWidth];
  uint32_t child[kWidth];
  int count = 0;  // children in use (2..kWidth), first `count` entries
};

struct BuildLeaf {
  uint32_t begin = 0;  // range of BuildTree::prims
  uint32_t count = 0;
};

struct BuildTree {
  // Nodes and leaves in creation order (which may vary between runs); walk the
  // tree from `root` for a deterministic order. The builder's own concurrent
  // arrays, handed over without a copy (a copy of the nodes, 13 bytes a
  // triangle, was the build's peak on a 10M-triangle mesh: docs/bench/scale.md).
  tbb::concurrent_vector<BuildNode> nodes;
  tbb::concurrent_vector<BuildLeaf> leaves;
  std::vector<uint32_t> prims;  // PrimRef ids, each leaf a contiguous range
  uint32_t root = kLeafRef;     // a node, or a leaf for a tiny input
  Bounds3f bounds;              // of all primitives
  bool empty() const { return prims.empty(); }
};

// Builds the tree over `refs` (consumed). An empty input gives an empty tree.
BuildTree build_tree(std::vector<PrimRef> refs, const BuildSettings& settings);

// Surface area of a box (0 for an empty box).
inline float surface_area(const Bounds3f& b) {
  if (b.empty()) return 0.0f;
  const Vec3f e = b.extent();
  return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
}

}  // namespace pt::bvh

// Bottom-level BVHs (one per triangle mesh, one over all analytic shapes) and
// the top level over them, in traversal layout, with their tree statistics.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "accel/bvh/analytic.h"
#include "accel/bvh/build.h"
#include "accel/bvh/huge_pages.h"
#include "accel/bvh/layout.h"
#include "geometry/shapes.h"

namespace pt::bvh {

// Statistics of one tree (or, summed, of all trees of a scene).
struct TreeStats {
  std::size_t nodes = 0;       // internal (8-wide) nodes
  std::size_t leaves = 0;
  std::size_t prims = 0;       // primitives in leaves
  std::size_t blocks = 0;      // leaf storage units: 4-triangle blocks, analytic shapes, BLAS references
  std::size_t child_slots_used = 0;  // children over all nodes (fill = child_slots_used / (8 nodes))
  int depth = 0;               // node levels above the deepest leaf (a lone leaf: 0)
  // leaf_sizes[k]: leaves holding k primitives (k = 1..16).
  std::array<std::size_t, kMaxLeafItems + 1> leaf_sizes{};
  // Expected cost of a ray through the root box, surface-area weighted: one
  // unit per node test and one per leaf block (Goldsmith and Salmon; MacDonald
  // and Booth): sum over nodes A(n)/A(root) + sum over leaves blocks(l) A(l)/A(root).
  double sah_cost = 0;
  std::size_t bytes = 0;       // nodes and leaf storage

  void add(const TreeStats& o);  // sums counts and bytes; depth is the maximum; SAH costs add
};

// The traversal arrays: large ones on huge pages (huge_pages.h).
using NodeArray = std::vector<Node8, HugePageAllocator<Node8>>;
using BlockArray = std::vector<TriangleBlock, HugePageAllocator<TriangleBlock>>;

struct Blas {
  NodeArray nodes;
  BlockArray blocks;  // kind Triangles
  std::vector<AnalyticPrim> prims;    // kind Analytic
  uint32_t root = kEmptyRef;
  BlasKind kind = BlasKind::Triangles;
  uint32_t object = 0;                // kind Triangles: the mesh's object id
  Bounds3f bounds;
  TreeStats stats;

  BlasData view() const {
    return BlasData{nodes.data(), root, kind, 0, blocks.data(), prims.data(), object, kNoInstanceId, nullptr};
  }
};

// The mesh must have valid indices (geometry_usable) and fewer than kMaxItems triangles.
Blas build_mesh_blas(const TriangleMesh& mesh, uint32_t object, const BuildSettings& settings);
// `prims[i]` has bounds `boxes[i]`.
Blas build_analytic_blas(std::vector<AnalyticPrim> prims, const std::vector<Bounds3f>& boxes,
                         const BuildSettings& settings);

// The top level: leaves index bottom-level BVHs (`boxes[i]` bounds BLAS i).
struct TopLevel {
  NodeArray nodes;
  uint32_t root = kEmptyRef;
  TreeStats stats;
};
TopLevel build_top_level(const std::vector<Bounds3f>& boxes, const BuildSettings& settings);

}  // namespace pt::bvh

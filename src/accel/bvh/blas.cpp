#include "accel/bvh/blas.h"

#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>

#include "core/function_ref.h"

namespace pt::bvh {

void TreeStats::add(const TreeStats& o) {
  nodes += o.nodes;
  leaves += o.leaves;
  prims += o.prims;
  blocks += o.blocks;
  child_slots_used += o.child_slots_used;
  depth = std::max(depth, o.depth);
  for (std::size_t k = 0; k < leaf_sizes.size(); ++k) leaf_sizes[k] += o.leaf_sizes[k];
  sah_cost += o.sah_cost;
  bytes += o.bytes;
}

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

uint32_t leaf_ref(uint32_t first, uint32_t items) {
  return kLeafBit | ((items - 1) << kLeafCountShift) | first;
}

// Emits the storage of one leaf (prims = its primitive ids) and returns the
// number of storage items (blocks) it used, which start at the returned
// `first`.
using LeafEmitter = FunctionRef<uint32_t(const uint32_t* prims, uint32_t count, uint32_t& first)>;

// Writes `tree` in depth-first order (each node before its children, the
// first child right after its parent) and gathers the statistics.
class Flattener {
 public:
  Flattener(const BuildTree& tree, NodeArray& out, TreeStats& stats, LeafEmitter emit)
      : tree_(tree), out_(out), stats_(stats), emit_(emit), root_area_(surface_area(tree.bounds)) {}

  uint32_t run() {
    if (tree_.empty()) return kEmptyRef;
    return visit(tree_.root, tree_.bounds, 0);
  }

 private:
  double weight(const Bounds3f& box) const {
    return root_area_ > 0.0f ? static_cast<double>(surface_area(box)) / root_area_ : 1.0;
  }

  uint32_t visit(uint32_t ref, const Bounds3f& box, int depth) {
    stats_.depth = std::max(stats_.depth, depth);
    if (ref & kLeafRef) {
      const BuildLeaf& leaf = tree_.leaves[ref & ~kLeafRef];
      uint32_t first = 0;
      const uint32_t items = emit_(tree_.prims.data() + leaf.begin, leaf.count, first);
      ++stats_.leaves;
      stats_.prims += leaf.count;
      stats_.blocks += items;
      ++stats_.leaf_sizes[std::min<std::size_t>(leaf.count, stats_.leaf_sizes.size() - 1)];
      stats_.sah_cost += weight(box) * items;
      return leaf_ref(first, items);
    }
    const BuildNode& node = tree_.nodes[ref];
    const auto index = static_cast<uint32_t>(out_.size());
    out_.emplace_back();
    ++stats_.nodes;
    stats_.child_slots_used += static_cast<std::size_t>(node.count);
    stats_.sah_cost += weight(box);
    uint32_t child[kWidth];
    for (int i = 0; i < kWidth; ++i) child[i] = kEmptyRef;
    for (int i = 0; i < node.count; ++i) child[i] = visit(node.child[i], node.box[i], depth + 1);
    Node8& n = out_[index];  // after the recursion: out_ may have grown
    for (int i = 0; i < kWidth; ++i) {
      const bool used = i < node.count;
      for (int a = 0; a < 3; ++a) {
        n.bounds[2 * a][i] = used ? node.box[i].lo[a] : kInf;
        n.bounds[2 * a + 1][i] = used ? node.box[i].hi[a] : -kInf;
      }
      n.child[i] = child[i];
    }
    return index;
  }

  const BuildTree& tree_;
  NodeArray& out_;
  TreeStats& stats_;
  LeafEmitter emit_;
  float root_area_;
};

// Writes the triangles prims[0, count) into ceil(count / 4) blocks.
void fill_blocks(const TriangleMesh& mesh, const uint32_t* prims, uint32_t count, TriangleBlock* out) {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (uint32_t b = 0; b < (count + 3) / 4; ++b) {
    TriangleBlock& block = out[b];
    for (uint32_t lane = 0; lane < 4; ++lane) {
      const uint32_t k = 4 * b + lane;
      block.prim[lane] = k < count ? prims[k] : kNoPrim;
      Vec3f p[3] = {Vec3f(kNaN), Vec3f(kNaN), Vec3f(kNaN)};
      if (k < count) {
        const uint32_t* idx = &mesh.indices[3 * static_cast<std::size_t>(prims[k])];
        for (int j = 0; j < 3; ++j) p[j] = mesh.positions[idx[j]];
        // The reference never reports an exactly degenerate triangle (its last
        // test, computed the same way): NaN vertices make every kernel skip it.
        if (cross(p[1] - p[0], p[2] - p[0]) == Vec3f(0.0f)) p[0] = p[1] = p[2] = Vec3f(kNaN);
      }
      for (int j = 0; j < 3; ++j) {
        for (int a = 0; a < 3; ++a) block.v[j][a][lane] = p[j][a];
      }
    }
  }
}

// Clamps user-facing settings to what the layout can encode.
BuildSettings sanitise(BuildSettings s, int leaf_block) {
  s.leaf_block = leaf_block;
  s.max_leaf_size = std::clamp(s.max_leaf_size, 1, static_cast<int>(kMaxLeafItems));
  return s;
}

}  // namespace

Blas build_mesh_blas(const TriangleMesh& mesh, uint32_t object, const BuildSettings& settings) {
  Blas blas;
  blas.kind = BlasKind::Triangles;
  blas.object = object;
  const auto n = static_cast<uint32_t>(mesh.triangle_count());
  std::vector<PrimRef> refs(n);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 4096), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t i = r.begin(); i != r.end(); ++i) refs[i] = PrimRef{bounds(mesh, i), i};
  });
  BuildTree tree = build_tree(std::move(refs), sanitise(settings, 4));
  blas.bounds = tree.bounds;

  // The flattening numbers the blocks in depth-first order; filling them
  // (reading the mesh) is then done in parallel.
  struct PendingLeaf {
    uint32_t begin, count, first_block;
  };
  std::vector<PendingLeaf> pending;
  uint32_t next_block = 0;
  auto emit = [&](const uint32_t* prims, uint32_t count, uint32_t& first) {
    first = next_block;
    pending.push_back(PendingLeaf{static_cast<uint32_t>(prims - tree.prims.data()), count, first});
    next_block += (count + 3) / 4;
    return (count + 3) / 4;
  };
  blas.nodes.reserve(tree.nodes.size());  // exact: no spare capacity from doubling
  pending.reserve(tree.leaves.size());
  blas.root = Flattener(tree, blas.nodes, blas.stats, emit).run();
  // The build's nodes and leaves are not needed any more: freed before the
  // blocks (the largest array) are allocated, so they never coexist.
  tbb::concurrent_vector<BuildNode>().swap(tree.nodes);
  tbb::concurrent_vector<BuildLeaf>().swap(tree.leaves);
  blas.blocks.resize(next_block);
  tbb::parallel_for(std::size_t{0}, pending.size(), [&](std::size_t l) {
    const PendingLeaf& leaf = pending[l];
    fill_blocks(mesh, tree.prims.data() + leaf.begin, leaf.count, &blas.blocks[leaf.first_block]);
  });
  blas.stats.bytes = blas.nodes.size() * sizeof(Node8) + blas.blocks.size() * sizeof(TriangleBlock);
  return blas;
}

Blas build_analytic_blas(std::vector<AnalyticPrim> prims, const std::vector<Bounds3f>& boxes,
                         const BuildSettings& settings) {
  Blas blas;
  blas.kind = BlasKind::Analytic;
  std::vector<PrimRef> refs(prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i) refs[i] = PrimRef{boxes[i], static_cast<uint32_t>(i)};
  const BuildTree tree = build_tree(std::move(refs), sanitise(settings, 1));
  blas.bounds = tree.bounds;
  auto emit = [&](const uint32_t* ids, uint32_t count, uint32_t& first) {
    first = static_cast<uint32_t>(blas.prims.size());
    for (uint32_t k = 0; k < count; ++k) blas.prims.push_back(prims[ids[k]]);
    return count;
  };
  blas.root = Flattener(tree, blas.nodes, blas.stats, emit).run();
  blas.stats.bytes = blas.nodes.size() * sizeof(Node8) + blas.prims.size() * sizeof(AnalyticPrim);
  return blas;
}

TopLevel build_top_level(const std::vector<Bounds3f>& boxes, const BuildSettings& settings) {
  TopLevel top;
  std::vector<PrimRef> refs(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) refs[i] = PrimRef{boxes[i], static_cast<uint32_t>(i)};
  BuildSettings s = sanitise(settings, 1);
  s.max_leaf_size = 1;  // a leaf is one bottom-level BVH
  const BuildTree tree = build_tree(std::move(refs), s);
  auto emit = [&](const uint32_t* ids, uint32_t count, uint32_t& first) {
    first = ids[0];
    return count;
  };
  top.root = Flattener(tree, top.nodes, top.stats, emit).run();
  top.stats.bytes = top.nodes.size() * sizeof(Node8);
  return top;
}

}  // namespace pt::bvh

#include "accel/bvh/build.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/concurrent_vector.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_group.h>

#include "accel/bvh/binning.h"

namespace pt::bvh {

namespace {

using detail::Range;
using detail::Split;
using detail::SplitKind;

// A range on its way to becoming a child: its split is decided when it is
// evaluated (kind None: it becomes a leaf).
struct Candidate {
  Range range;
  Split split;
  float area = 0;
  bool leaf() const { return split.kind == SplitKind::None; }
};

class Builder {
 public:
  Builder(PrimRef* refs, const BuildSettings& settings, BuildTree& tree)
      : refs_(refs), s_(settings), nodes_(tree.nodes), leaves_(tree.leaves) {}

  // Decides whether `r`, as a node at level `depth`, is a leaf or how it splits.
  Candidate evaluate(const Range& r, int depth) const;
  // Builds the subtree of `c` at level `depth`; returns its reference.
  uint32_t build(const Candidate& c, int depth);

 private:
  uint32_t make_leaf(const Range& r) {
    const auto it = leaves_.push_back(BuildLeaf{r.begin, r.size()});
    return kLeafRef | static_cast<uint32_t>(it - leaves_.begin());
  }

  PrimRef* refs_;
  const BuildSettings& s_;
  tbb::concurrent_vector<BuildNode>& nodes_;
  tbb::concurrent_vector<BuildLeaf>& leaves_;
};

Candidate Builder::evaluate(const Range& r, int depth) const {
  Candidate c{r, Split{}, surface_area(r.box)};
  const uint32_t n = r.size();
  if (n <= 1) return c;
  const bool fits = n <= static_cast<uint32_t>(s_.max_leaf_size);
  // One block's worth: a split costs at least node_cost + block_cost times a
  // positive area ratio, more than the leaf's block_cost when node_cost >= block_cost.
  if (fits && n <= static_cast<uint32_t>(s_.leaf_block) && s_.node_cost >= s_.block_cost) return c;
  if (depth >= kMedianDepth) {
    if (!fits) c.split.kind = SplitKind::Median;  // halving bounds the depth
    return c;
  }
  const Split split = detail::find_sah_split(refs_, r, s_);
  if (split.kind == SplitKind::None) {  // every centre coincides
    if (!fits) c.split.kind = SplitKind::Median;
    return c;
  }
  if (fits) {
    if (!(c.area > 0.0f)) return c;
    const float split_cost = s_.node_cost + split.cost / c.area;
    if (detail::leaf_cost(n, s_) <= split_cost) return c;
  }
  c.split = split;
  return c;
}

uint32_t Builder::build(const Candidate& root, int depth) {
  if (root.leaf()) return make_leaf(root.range);

  // Fill the node: split the splittable child of largest area until the node
  // is full or every child is a leaf.
  Candidate child[kWidth];
  int count = 1;
  child[0] = root;
  while (count < kWidth) {
    int pick = -1;
    float best = -1.0f;
    for (int i = 0; i < count; ++i) {
      if (!child[i].leaf() && child[i].area > best) {
        best = child[i].area;
        pick = i;
      }
    }
    if (pick < 0) break;
    const auto [left, right] = detail::apply_split(refs_, child[pick].range, child[pick].split, s_);
    child[pick] = evaluate(left, depth + 1);
    child[count++] = evaluate(right, depth + 1);
  }

  BuildNode node;
  node.count = count;
  for (int i = 0; i < kWidth; ++i) node.child[i] = kLeafRef;
  bool parallel = false;
  for (int i = 0; i < count; ++i) {
    node.box[i] = child[i].range.box;
    parallel |= !child[i].leaf() && child[i].range.size() > s_.parallel_threshold;
  }
  if (parallel) {
    tbb::task_group tasks;
    for (int i = 0; i < count; ++i) {
      if (child[i].leaf()) {
        node.child[i] = make_leaf(child[i].range);
      } else if (child[i].range.size() > s_.parallel_threshold) {
        tasks.run([this, &node, &child, i, depth] { node.child[i] = build(child[i], depth + 1); });
      } else {
        node.child[i] = build(child[i], depth + 1);
      }
    }
    tasks.wait();
  } else {
    for (int i = 0; i < count; ++i) node.child[i] = build(child[i], depth + 1);
  }
  const auto it = nodes_.push_back(node);
  return static_cast<uint32_t>(it - nodes_.begin());
}

Range whole_range(const PrimRef* refs, uint32_t n) {
  if (n < 65536) return detail::make_range(refs, 0, n);
  return tbb::parallel_reduce(
      tbb::blocked_range<uint32_t>(0, n, 16384), Range{0, n, {}, {}},
      [&](const tbb::blocked_range<uint32_t>& r, Range acc) {
        const Range part = detail::make_range(refs, r.begin(), r.end());
        acc.box.extend(part.box);
        acc.cbox.extend(part.cbox);
        return acc;
      },
      [](Range a, const Range& b) {
        a.box.extend(b.box);
        a.cbox.extend(b.cbox);
        return a;
      });
}

}  // namespace

BuildTree build_tree(std::vector<PrimRef> refs, const BuildSettings& settings) {
  BuildTree tree;
  if (refs.empty()) return tree;
  const auto n = static_cast<uint32_t>(refs.size());
  Builder builder(refs.data(), settings, tree);
  const Range all = whole_range(refs.data(), n);
  tree.bounds = all.box;
  tree.root = builder.build(builder.evaluate(all, 0), 0);
  tree.prims.resize(n);
  for (uint32_t i = 0; i < n; ++i) tree.prims[i] = refs[i].id;
  return tree;
}

}  // namespace pt::bvh

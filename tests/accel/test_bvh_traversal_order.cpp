// The order of the BVH's nearest-hit loop (accel/bvh/kernel.h), driven by a
// scripted node test: hit children are visited nearest first, ties in slot
// order, whatever their number (two children take a path of their own), and a
// pushed child whose entry lies beyond a hit found meanwhile is skipped. The
// kernels share this loop; test_bvh.cpp checks them against each other and the
// reference on real trees, where the order shows only in the work counted.
#include <gtest/gtest.h>

#include <cstddef>
#include <map>
#include <vector>

#include "accel/bvh/kernel.h"

namespace pt::bvh {
namespace {

constexpr float kMissed = -1.0f;

// Node i's children: entry distances per slot (kMissed: the ray misses the
// box); a child is hit when its distance is at most the widened tmax passed in.
struct ScriptedOps {
  const Node8* base = nullptr;
  std::vector<std::vector<float>> dist;
  mutable std::vector<float> tmax_exit_seen;

  uint32_t intersect_node(const Node8& node, float tmax_exit, float* out) const {
    const std::vector<float>& d = dist[static_cast<std::size_t>(&node - base)];
    tmax_exit_seen.push_back(tmax_exit);
    uint32_t mask = 0;
    for (uint32_t i = 0; i < 8; ++i) {
      out[i] = d[i];
      if (d[i] != kMissed && d[i] <= tmax_exit) mask |= 1u << i;
    }
    return mask;
  }
};

uint32_t leaf_ref(uint32_t item) { return kLeafBit | item; }

struct Tree {
  std::vector<Node8> nodes;
  ScriptedOps ops;

  explicit Tree(std::size_t n) : nodes(n) {
    for (Node8& node : nodes) {
      for (uint32_t& c : node.child) c = kEmptyRef;
    }
    ops.base = nodes.data();
    ops.dist.assign(n, std::vector<float>(8, kMissed));
  }
  void set(uint32_t node, uint32_t slot, uint32_t ref, float dist) {
    nodes[node].child[slot] = ref;
    ops.dist[node][slot] = dist;
  }

  // The leaves visited in order, from node 0; `hits` gives the t at which a
  // leaf's item is hit (the leaf lowers q.tmax to it, as a leaf test does).
  std::vector<uint32_t> leaves_visited(const std::map<uint32_t, float>& hits = {}, float tmax = 100.0f) {
    RayQuery q{};
    q.tmin = 0.0f;
    q.tmax = tmax;
    std::vector<uint32_t> order;
    kernel::traverse<false, false>(ops, nodes.data(), 0, q, nullptr, [&](uint32_t ref) {
      const uint32_t item = ref & kLeafIndexMask;
      order.push_back(item);
      const auto it = hits.find(item);
      if (it == hits.end() || !(it->second < q.tmax)) return false;
      q.tmax = it->second;
      return true;
    });
    return order;
  }
};

TEST(BvhTraversalOrder, TwoHitChildrenNearestFirst) {
  Tree t(1);
  t.set(0, 2, leaf_ref(20), 5.0f);
  t.set(0, 5, leaf_ref(50), 3.0f);
  EXPECT_EQ(t.leaves_visited(), (std::vector<uint32_t>{50, 20}));

  Tree u(1);  // already in order
  u.set(0, 1, leaf_ref(10), 1.0f);
  u.set(0, 6, leaf_ref(60), 2.0f);
  EXPECT_EQ(u.leaves_visited(), (std::vector<uint32_t>{10, 60}));
}

TEST(BvhTraversalOrder, TiesGoInSlotOrder) {
  Tree t(1);
  t.set(0, 3, leaf_ref(30), 4.0f);
  t.set(0, 7, leaf_ref(70), 4.0f);
  EXPECT_EQ(t.leaves_visited(), (std::vector<uint32_t>{30, 70}));

  Tree u(1);  // three and more: the insertion sort, equally stable
  u.set(0, 0, leaf_ref(0), 7.0f);
  u.set(0, 1, leaf_ref(1), 2.0f);
  u.set(0, 2, leaf_ref(2), 7.0f);
  u.set(0, 4, leaf_ref(4), 0.5f);
  EXPECT_EQ(u.leaves_visited(), (std::vector<uint32_t>{4, 1, 0, 2}));
}

TEST(BvhTraversalOrder, InnerNodesOfTwoHitChildrenDescendNearestFirst) {
  // Node 0: node 1 at 6, node 2 at 1; each holds two leaves.
  Tree t(3);
  t.set(0, 0, 1, 6.0f);
  t.set(0, 4, 2, 1.0f);
  t.set(1, 0, leaf_ref(10), 9.0f);
  t.set(1, 1, leaf_ref(11), 6.5f);
  t.set(2, 0, leaf_ref(20), 3.0f);
  t.set(2, 7, leaf_ref(27), 1.5f);
  EXPECT_EQ(t.leaves_visited(), (std::vector<uint32_t>{27, 20, 11, 10}));
}

TEST(BvhTraversalOrder, PushedChildBeyondANewHitIsSkipped) {
  // The nearer leaf's hit at t = 5 lowers tmax: the pushed leaf entered at 10
  // is not visited, and node tests after the hit see the lowered tmax.
  Tree t(1);
  t.set(0, 0, leaf_ref(0), 1.0f);
  t.set(0, 1, leaf_ref(1), 10.0f);
  EXPECT_EQ(t.leaves_visited({{0, 5.0f}}), (std::vector<uint32_t>{0}));
  EXPECT_EQ(t.leaves_visited({{0, 50.0f}}), (std::vector<uint32_t>{0, 1}));

  // Node 0: leaf 0 at 1 (hit at 5), node 1 at 2 (whose children lie at 3 and 8).
  Tree u(2);
  u.set(0, 0, leaf_ref(0), 1.0f);
  u.set(0, 1, 1, 2.0f);
  u.set(1, 0, leaf_ref(10), 3.0f);
  u.set(1, 1, leaf_ref(11), 8.0f);
  EXPECT_EQ(u.leaves_visited({{0, 5.0f}}), (std::vector<uint32_t>{0, 10}));
  ASSERT_EQ(u.ops.tmax_exit_seen.size(), 2u);
  EXPECT_EQ(u.ops.tmax_exit_seen[0], 100.0f * kernel::kExitScale);
  EXPECT_EQ(u.ops.tmax_exit_seen[1], 5.0f * kernel::kExitScale);
}

}  // namespace
}  // namespace pt::bvh

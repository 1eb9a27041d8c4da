// A bounding volume hierarchy over the bounded lights (point, spot, area
// lights, each emissive shape of each instance), for choosing one light in
// proportion to its importance at a shading point (the idea of pbrt-v4's
// BVHLightSampler; docs/path-tracing.md, "Choosing a light").
//
// Built as a binary tree, top-down by the surface area orientation heuristic
// (Conty Estevez and Kulla 2018): a split is scored by intensity x orientation
// measure x surface area of each side, over 12 buckets of the centroids on each
// axis. The binary tree is then collapsed into a 4-wide one (each node takes
// up to four of the binary tree's nodes below it, the largest first), whose
// nodes keep their children's bounds side by side (ImportanceBounds4), so that
// one evaluation of four lanes replaces the binary tree's two levels of two.
//
// choose() walks from the root, at each node taking a child with probability
// proportional to its importance at (p, n); the light's probability is the
// product of the choices on its way. pmf() recomputes that product for a given
// light from its leaf up (each node knows its parent and its slot there), so
// that a light found by a BSDF ray gets the same probability as choose() would
// have given it (multiple importance sampling).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "render/lights/light_bounds.h"

namespace pt {

class LightBvh {
 public:
  struct Entry {
    int light;  // the light's index in its set
    LightBounds bounds;
  };

  LightBvh() = default;
  // `entries`: the lights with positive intensity; `light_count`: the size of
  // the set their indices refer to.
  LightBvh(std::vector<Entry> entries, std::size_t light_count);

  bool empty() const { return nodes_.empty(); }
  // The number of (4-wide) nodes and of lights in the tree.
  std::size_t node_count() const { return nodes_.size(); }
  std::size_t light_count() const { return lights_; }
  // The root's importance at (p, n): an estimate of the irradiance all these lights send there.
  float importance(Vec3f p, Vec3f n) const { return nodes_.empty() ? 0.0f : root_.importance(p, n); }
  // The depth of the deepest light (the root's children are at depth 1).
  int depth() const;
  // A light picked by importance at (p, n), with its probability; -1 (pmf 0)
  // when the walk meets a node whose children all have importance 0 (which
  // includes any point where importance(p, n) is 0: the caller, LightSet,
  // weighs the tree by that, so it need not be computed here again).
  int choose(Vec3f p, Vec3f n, float u, float& pmf) const;
  // The probability that choose(p, n, ...) returns `light` (0 for a light not in the tree).
  float pmf(Vec3f p, Vec3f n, int light) const;

 private:
  static constexpr uint32_t kNone = 0xffffffffu;
  struct Node {
    ImportanceBounds4 children;  // empty lanes have intensity 0
    std::array<int32_t, 4> child{-1, -1, -1, -1};  // >= 0: a node; < 0: the light ~child (a leaf)
    uint32_t parent = kNone;
    uint32_t slot = 0;  // its lane in the parent
  };
  struct Binary;  // the binary tree the build makes first (light_bvh.cpp)
  uint32_t collapse(const std::vector<Binary>& binary, uint32_t b, uint32_t parent, uint32_t slot);

  ImportanceBounds root_;
  std::vector<Node> nodes_;
  std::vector<uint32_t> leaf_of_;  // per light of the set: 4 x its node + its lane, or kNone
  std::size_t lights_ = 0;
};

}  // namespace pt

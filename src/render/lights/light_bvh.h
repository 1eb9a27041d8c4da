// A bounding volume hierarchy over the bounded lights (point, spot, area
// lights, each emissive shape of each instance), for choosing one light in
// proportion to its importance at a shading point (the idea of pbrt-v4's
// BVHLightSampler; docs/path-tracing.md, "Choosing a light").
//
// Every node holds the LightBounds of the lights below it. choose() walks
// from the root, at each node taking a child with probability proportional to
// its importance at (p, n); the light's probability is the product of the
// choices on its way. pmf() recomputes that product for a given light from its
// leaf up (each node knows its parent), so that a light found by a BSDF ray
// gets the same probability as choose() would have given it (multiple
// importance sampling).
//
// Built top-down by the surface area orientation heuristic (Conty Estevez and
// Kulla 2018): a split is scored by intensity x orientation measure x surface
// area of each side, over 12 buckets of the centroids on each axis.
#pragma once

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
  std::size_t node_count() const { return nodes_.size(); }
  // The root's importance at (p, n): an estimate of the irradiance all these lights send there.
  float importance(Vec3f p, Vec3f n) const { return nodes_.empty() ? 0.0f : nodes_[0].bounds.importance(p, n); }
  // The depth of the deepest leaf (the root's is 0).
  int depth() const;
  // A light picked by importance at (p, n), with its probability; -1 (pmf 0)
  // when the walk meets a node whose children both have importance 0.
  int choose(Vec3f p, Vec3f n, float u, float& pmf) const;
  // The probability that choose(p, n, ...) returns `light` (0 for a light not in the tree).
  float pmf(Vec3f p, Vec3f n, int light) const;

 private:
  static constexpr uint32_t kNone = 0xffffffffu;
  struct Node {
    ImportanceBounds bounds;
    uint32_t parent = kNone;
    uint32_t second = kNone;  // the second child (the first is the next node); kNone at a leaf
    int light = -1;           // a leaf's light
  };
  // Builds the subtree of entries [begin, end); returns its node and, in `out`, its bounds.
  uint32_t build(std::vector<Entry>& entries, std::size_t begin, std::size_t end, uint32_t parent, LightBounds& out);
  // The probability of taking `child` at its parent, at (p, n).
  float child_probability(uint32_t child, Vec3f p, Vec3f n) const;

  std::vector<Node> nodes_;
  std::vector<uint32_t> leaf_of_;  // per light of the set: its leaf, or kNone
};

}  // namespace pt

#include "render/lights/light_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/sampling.h"

namespace pt {

namespace {

constexpr int kBuckets = 12;

// The orientation measure of a bounds' emission: the integral over the
// directions it may emit into, weighted by the cosine falloff past theta_o
// (Conty Estevez and Kulla 2018, eq. 1).
float orientation_measure(const LightBounds& b) {
  const float theta_o = std::acos(std::clamp(b.normals.cos_theta, -1.0f, 1.0f));
  const float theta_e = std::acos(std::clamp(b.cos_theta_e, -1.0f, 1.0f));
  const float theta_w = std::min(theta_o + theta_e, kPi);
  const float sin_o = std::sin(theta_o), cos_o = std::cos(theta_o);
  return 2.0f * kPi * (1.0f - cos_o) +
         0.5f * kPi * (2.0f * theta_w * sin_o - std::cos(theta_o - 2.0f * theta_w) - 2.0f * theta_o * sin_o + cos_o);
}

float surface_area(const Bounds3f& b) {
  const Vec3f e = b.extent();
  return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
}

float split_cost(const LightBounds& b) { return b.intensity * orientation_measure(b) * surface_area(b.bounds); }

struct Split {
  int axis = -1;
  int bucket = 0;  // buckets [0, bucket] go first
  float cost = kInfinity;
};

Split best_split(const std::vector<LightBvh::Entry>& e, std::size_t begin, std::size_t end, const Bounds3f& centroids) {
  Split best;
  const Vec3f extent = centroids.extent();
  const float max_extent = max_component(extent);
  for (int axis = 0; axis < 3; ++axis) {
    if (!(extent[axis] > 0.0f)) continue;
    std::array<LightBounds, kBuckets> buckets{};
    for (std::size_t i = begin; i < end; ++i) {
      const float t = (e[i].bounds.bounds.centre()[axis] - centroids.lo[axis]) / extent[axis];
      const int k = std::clamp(static_cast<int>(t * kBuckets), 0, kBuckets - 1);
      buckets[k] = bounds_union(buckets[k], e[i].bounds);
    }
    // Regularised as pbrt-v4 does: thin boxes split across their long side.
    const float kr = max_extent / extent[axis];
    for (int k = 0; k + 1 < kBuckets; ++k) {
      LightBounds lo, hi;
      for (int j = 0; j <= k; ++j) lo = bounds_union(lo, buckets[j]);
      for (int j = k + 1; j < kBuckets; ++j) hi = bounds_union(hi, buckets[j]);
      if (!(lo.intensity > 0.0f) || !(hi.intensity > 0.0f)) continue;
      const float cost = kr * (split_cost(lo) + split_cost(hi));
      if (cost < best.cost) best = {axis, k, cost};
    }
  }
  return best;
}

}  // namespace

struct LightBvh::Binary {
  LightBounds bounds;
  uint32_t second = kNone;  // the second child (the first is the next node); kNone at a leaf
  int light = -1;           // a leaf's light
};

namespace {

std::size_t split_entries(std::vector<LightBvh::Entry>& e, std::size_t begin, std::size_t end) {
  Bounds3f centroids;
  for (std::size_t i = begin; i < end; ++i) centroids.extend(e[i].bounds.bounds.centre());
  const Split split = best_split(e, begin, end, centroids);
  std::size_t mid = begin + (end - begin) / 2;
  if (split.axis >= 0) {
    const int axis = split.axis;
    const float lo = centroids.lo[axis], extent = centroids.extent()[axis];
    const auto first = [&](const LightBvh::Entry& x) {
      const float t = (x.bounds.bounds.centre()[axis] - lo) / extent;
      return std::clamp(static_cast<int>(t * kBuckets), 0, kBuckets - 1) <= split.bucket;
    };
    mid = static_cast<std::size_t>(std::partition(e.begin() + static_cast<std::ptrdiff_t>(begin),
                                                  e.begin() + static_cast<std::ptrdiff_t>(end), first) -
                                   e.begin());
    if (mid == begin || mid == end) mid = begin + (end - begin) / 2;
  }
  return mid;  // equal centroids (or no better split): halves in the given order
}

template <class Binary>
uint32_t build_binary(std::vector<LightBvh::Entry>& e, std::size_t begin, std::size_t end,
                      std::vector<Binary>& nodes) {
  const auto index = static_cast<uint32_t>(nodes.size());
  nodes.emplace_back();
  if (end - begin == 1) {
    nodes[index].bounds = e[begin].bounds;
    nodes[index].light = e[begin].light;
    return index;
  }
  const std::size_t mid = split_entries(e, begin, end);
  build_binary(e, begin, mid, nodes);
  const uint32_t second = build_binary(e, mid, end, nodes);
  nodes[index].second = second;
  nodes[index].bounds = bounds_union(nodes[index + 1].bounds, nodes[second].bounds);
  return index;
}

}  // namespace

LightBvh::LightBvh(std::vector<Entry> entries, std::size_t light_count) : leaf_of_(light_count, kNone) {
  std::erase_if(entries, [](const Entry& e) { return !(e.bounds.intensity > 0.0f); });
  if (entries.empty()) return;
  lights_ = entries.size();
  std::vector<Binary> binary;
  binary.reserve(2 * entries.size() - 1);
  build_binary(entries, 0, entries.size(), binary);
  root_ = ImportanceBounds(binary[0].bounds);
  nodes_.reserve(entries.size());
  collapse(binary, 0, kNone, 0);
}

// Node b of the binary tree as a 4-wide node: its children, and while there
// are fewer than four, the largest (by surface area) inner one replaced by its two.
uint32_t LightBvh::collapse(const std::vector<Binary>& binary, uint32_t b, uint32_t parent, uint32_t slot) {
  std::array<uint32_t, 4> kids{b, kNone, kNone, kNone};
  int count = 1;
  if (binary[b].second != kNone) kids = {b + 1, binary[b].second, kNone, kNone}, count = 2;
  while (count < 4) {
    int widest = -1;
    float widest_area = -1.0f;
    for (int k = 0; k < count; ++k) {
      if (binary[kids[k]].second == kNone) continue;
      const float area = surface_area(binary[kids[k]].bounds.bounds);
      if (area > widest_area) widest = k, widest_area = area;
    }
    if (widest < 0) break;
    const uint32_t inner = kids[widest];
    kids[widest] = inner + 1;
    kids[count++] = binary[inner].second;
  }
  const auto index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_[index].parent = parent;
  nodes_[index].slot = slot;
  for (int k = 0; k < count; ++k) {
    const Binary& kid = binary[kids[k]];
    nodes_[index].children.set(k, ImportanceBounds(kid.bounds));
    if (kid.second == kNone) {
      nodes_[index].child[k] = ~kid.light;
      leaf_of_[static_cast<std::size_t>(kid.light)] = 4 * index + static_cast<uint32_t>(k);
    } else {
      const uint32_t child = collapse(binary, kids[k], index, static_cast<uint32_t>(k));
      nodes_[index].child[k] = static_cast<int32_t>(child);
    }
  }
  return index;
}

int LightBvh::depth() const {
  int deepest = 0;
  for (uint32_t leaf : leaf_of_) {
    if (leaf == kNone) continue;
    int d = 1;
    for (uint32_t node = leaf / 4; node != 0; node = nodes_[node].parent) ++d;
    deepest = std::max(deepest, d);
  }
  return deepest;
}

int LightBvh::choose(Vec3f p, Vec3f n, float u, float& pmf) const {
  pmf = 0.0f;
  if (nodes_.empty()) return -1;
  float prob = 1.0f;
  uint32_t node = 0;
  alignas(16) float importance[4];
  for (;;) {
    const Node& at = nodes_[node];
    at.children.importance(p, n, importance);
    const float total = (importance[0] + importance[1]) + (importance[2] + importance[3]);
    if (!(total > 0.0f)) return -1;
    // The lane whose share of [0, total) holds u * total (lanes of importance 0
    // have none); u rescaled to [0, 1) within it.
    int last = 3;
    while (!(importance[last] > 0.0f)) --last;
    const float target = u * total;
    int k = 0;
    float below = 0.0f;
    while (k < last && below + importance[k] <= target) below += importance[k++];
    u = std::clamp((target - below) / importance[k], 0.0f, kOneMinusEpsilon);
    prob *= importance[k] / total;
    if (at.child[k] < 0) {
      pmf = prob;
      return ~at.child[k];
    }
    node = static_cast<uint32_t>(at.child[k]);
  }
}

float LightBvh::pmf(Vec3f p, Vec3f n, int light) const {
  if (light < 0 || static_cast<std::size_t>(light) >= leaf_of_.size()) return 0.0f;
  const uint32_t leaf = leaf_of_[static_cast<std::size_t>(light)];
  if (leaf == kNone) return 0.0f;
  float prob = 1.0f;
  alignas(16) float importance[4];
  uint32_t slot = leaf % 4;
  for (uint32_t node = leaf / 4; node != kNone; node = nodes_[node].parent) {
    nodes_[node].children.importance(p, n, importance);
    const float total = (importance[0] + importance[1]) + (importance[2] + importance[3]);
    if (!(total > 0.0f) || !(importance[slot] > 0.0f)) return 0.0f;
    prob *= importance[slot] / total;
    slot = nodes_[node].slot;
  }
  return prob;
}

}  // namespace pt

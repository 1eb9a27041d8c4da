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

LightBvh::LightBvh(std::vector<Entry> entries, std::size_t light_count) : leaf_of_(light_count, kNone) {
  std::erase_if(entries, [](const Entry& e) { return !(e.bounds.intensity > 0.0f); });
  if (entries.empty()) return;
  nodes_.reserve(2 * entries.size() - 1);
  LightBounds all;
  build(entries, 0, entries.size(), kNone, all);
}

int LightBvh::depth() const {
  int deepest = 0;
  for (uint32_t leaf : leaf_of_) {
    if (leaf == kNone) continue;
    int d = 0;
    for (uint32_t node = leaf; node != 0; node = nodes_[node].parent) ++d;
    deepest = std::max(deepest, d);
  }
  return deepest;
}

uint32_t LightBvh::build(std::vector<Entry>& e, std::size_t begin, std::size_t end, uint32_t parent,
                         LightBounds& out) {
  const auto index = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_[index].parent = parent;
  if (end - begin == 1) {
    out = e[begin].bounds;
    nodes_[index].bounds = ImportanceBounds(out);
    nodes_[index].light = e[begin].light;
    leaf_of_[static_cast<std::size_t>(e[begin].light)] = index;
    return index;
  }
  Bounds3f centroids;
  for (std::size_t i = begin; i < end; ++i) centroids.extend(e[i].bounds.bounds.centre());
  const Split split = best_split(e, begin, end, centroids);
  std::size_t mid = begin + (end - begin) / 2;
  if (split.axis >= 0) {
    const int axis = split.axis;
    const float lo = centroids.lo[axis], extent = centroids.extent()[axis];
    const auto first = [&](const Entry& x) {
      const float t = (x.bounds.bounds.centre()[axis] - lo) / extent;
      return std::clamp(static_cast<int>(t * kBuckets), 0, kBuckets - 1) <= split.bucket;
    };
    mid = static_cast<std::size_t>(std::partition(e.begin() + static_cast<std::ptrdiff_t>(begin),
                                                  e.begin() + static_cast<std::ptrdiff_t>(end), first) -
                                   e.begin());
    if (mid == begin || mid == end) mid = begin + (end - begin) / 2;
  }
  // Equal centroids (or no better split): halves in the given order.
  LightBounds first_bounds, second_bounds;
  build(e, begin, mid, index, first_bounds);
  const uint32_t second = build(e, mid, end, index, second_bounds);
  nodes_[index].second = second;
  out = bounds_union(first_bounds, second_bounds);
  nodes_[index].bounds = ImportanceBounds(out);
  return index;
}

int LightBvh::choose(Vec3f p, Vec3f n, float u, float& pmf) const {
  pmf = 0.0f;
  if (nodes_.empty() || !(nodes_[0].bounds.importance(p, n) > 0.0f)) return -1;
  float prob = 1.0f;
  uint32_t node = 0;
  while (nodes_[node].second != kNone) {
    const float a = nodes_[node + 1].bounds.importance(p, n);
    const float b = nodes_[nodes_[node].second].bounds.importance(p, n);
    if (!(a + b > 0.0f)) return -1;
    const float pa = a / (a + b);
    if (u < pa) {
      u = std::min(u / pa, kOneMinusEpsilon);
      prob *= pa;
      node = node + 1;
    } else {
      u = std::min((u - pa) / (1.0f - pa), kOneMinusEpsilon);
      prob *= 1.0f - pa;
      node = nodes_[node].second;
    }
  }
  pmf = prob;
  return nodes_[node].light;
}

float LightBvh::child_probability(uint32_t child, Vec3f p, Vec3f n) const {
  const uint32_t parent = nodes_[child].parent;
  const float a = nodes_[parent + 1].bounds.importance(p, n);
  const float b = nodes_[nodes_[parent].second].bounds.importance(p, n);
  if (!(a + b > 0.0f)) return 0.0f;
  const float pa = a / (a + b);
  return child == parent + 1 ? pa : 1.0f - pa;
}

float LightBvh::pmf(Vec3f p, Vec3f n, int light) const {
  if (light < 0 || static_cast<std::size_t>(light) >= leaf_of_.size()) return 0.0f;
  uint32_t node = leaf_of_[static_cast<std::size_t>(light)];
  if (node == kNone || !(nodes_[0].bounds.importance(p, n) > 0.0f)) return 0.0f;
  float prob = 1.0f;
  for (; node != 0; node = nodes_[node].parent) {
    prob *= child_probability(node, p, n);
    if (!(prob > 0.0f)) return 0.0f;
  }
  return prob;
}

}  // namespace pt

// What the guides (light_guide.h, path_guide.h) share: the camera ray of a
// pre-pass path, the pre-pass run over a worker pool with the records kept in
// path order, and a binary tree over space that splits the records' bounds at
// the middle of the longest axis until a leaf holds few enough of them.
//
// A pre-pass path's numbers come from an Rng seeded by (seed, key, path
// index), so the records, and everything learned from them, depend on the
// seed alone: not on the thread count nor on the render's sampler.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/parallel.h"
#include "core/rng.h"
#include "geometry/shapes.h"
#include "render/render_scene.h"

namespace pt {

// A camera ray through a uniformly random film position (and lens position).
inline Ray prepass_camera_ray(const RenderScene& scene, Rng& rng) {
  const Vec2f film(rng.next_float() * static_cast<float>(scene.width),
                   rng.next_float() * static_cast<float>(scene.height));
  return scene.camera.has_lens() ? scene.camera.generate_ray(film, Vec2f(rng.next_float(), rng.next_float()))
                                 : scene.camera.generate_ray(film);
}

// The shadow ray of a light sample taken at sg.
inline Ray light_shadow_ray(const SurfaceGeometry& sg, const LightSample& ls) {
  if (ls.infinite) return spawn_ray(sg, ls.wi);
  if (ls.delta) return spawn_ray_to(sg, ls.p_light);
  return spawn_ray_to(sg, offset_ray_origin(ls.p_light, ls.n_light, -ls.wi));
}

// Runs trace(rng, out) for paths 0 .. paths - 1 in `pool`; returns the
// records in path order.
template <class Record, class Trace>
std::vector<Record> run_prepass(WorkerPool& pool, int64_t paths, uint64_t seed, uint64_t key, const Trace& trace) {
  constexpr int64_t kPathsPerTask = 64;
  const int64_t tasks = (paths + kPathsPerTask - 1) / kPathsPerTask;
  std::vector<std::vector<Record>> parts(static_cast<std::size_t>(tasks));
  pool.run([&] {
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, tasks), [&](const tbb::blocked_range<int64_t>& r) {
      for (int64_t task = r.begin(); task != r.end(); ++task) {
        auto& out = parts[static_cast<std::size_t>(task)];
        const int64_t end = std::min(paths, (task + 1) * kPathsPerTask);
        for (int64_t path = task * kPathsPerTask; path < end; ++path) {
          Rng rng(hash_keys(seed, key, static_cast<uint64_t>(path)));
          trace(rng, out);
        }
      }
    });
  });
  std::size_t total = 0;
  for (const auto& part : parts) total += part.size();
  std::vector<Record> records;
  records.reserve(total);
  for (const auto& part : parts) records.insert(records.end(), part.begin(), part.end());
  return records;
}

// The midpoint tree over records with a position `p`.
class SpatialTree {
 public:
  bool empty() const { return nodes_.empty(); }
  // Splits [records) (reordered, stably) until a leaf holds at most
  // `leaf_records` or the depth reaches kMaxDepth; calls learn(first, count)
  // for each leaf in order, whose index is the number of earlier calls.
  template <class Record, class Learn>
  void build(std::vector<Record>& records, std::size_t leaf_records, const Learn& learn) {
    nodes_.clear();
    leaves_ = 0;
    if (records.empty()) return;
    Bounds3f bounds;
    for (const Record& r : records) bounds.extend(r.p);
    split(records, 0, records.size(), bounds, 0, leaf_records, learn);
  }
  // The index of the leaf holding p (the tree must not be empty).
  int leaf(Vec3f p) const {
    const Node* node = &nodes_[0];
    while (node->axis >= 0) node = &nodes_[static_cast<std::size_t>(axis_of(p, node->axis) < node->split ? node->a : node->b)];
    return node->a;
  }

 private:
  static constexpr int kMaxDepth = 24;
  struct Node {
    int axis = -1;  // -1: a leaf
    float split = 0.0f;
    int a = 0;  // a leaf: its index; else the child below the split
    int b = 0;  // the child at or above it
  };
  static float axis_of(Vec3f v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

  template <class Record, class Learn>
  int split(std::vector<Record>& records, std::size_t begin, std::size_t end, const Bounds3f& bounds, int depth,
            std::size_t leaf_records, const Learn& learn) {
    const int node = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    const Vec3f e = bounds.extent();
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
    if (end - begin <= leaf_records || depth >= kMaxDepth || !(axis_of(e, axis) > 0.0f)) {
      nodes_[static_cast<std::size_t>(node)].a = leaves_++;
      learn(records.data() + begin, end - begin);
      return node;
    }
    const float at = axis_of(bounds.centre(), axis);
    const auto mid = std::stable_partition(records.begin() + static_cast<std::ptrdiff_t>(begin),
                                           records.begin() + static_cast<std::ptrdiff_t>(end),
                                           [&](const Record& r) { return axis_of(r.p, axis) < at; });
    const std::size_t m = static_cast<std::size_t>(mid - records.begin());
    Bounds3f left = bounds, right = bounds;
    (axis == 0 ? left.hi.x : axis == 1 ? left.hi.y : left.hi.z) = at;
    (axis == 0 ? right.lo.x : axis == 1 ? right.lo.y : right.lo.z) = at;
    const int a = split(records, begin, m, left, depth + 1, leaf_records, learn);
    const int b = split(records, m, end, right, depth + 1, leaf_records, learn);
    nodes_[static_cast<std::size_t>(node)] = {axis, at, a, b};
    return node;
  }

  std::vector<Node> nodes_;
  int leaves_ = 0;
};

}  // namespace pt

#include "accel/bvh/bvh_accel.h"

#include <cassert>
#include <chrono>
#include <cmath>
#include <type_traits>
#include <variant>

#include <tbb/parallel_for.h>

#include "accel/bvh/kernels.h"
#include "accel/bvh/ray_frame.h"
#include "core/parallel.h"
#include "geometry/float_util.h"

namespace pt::bvh {

namespace {

// Prepares `ray` for the kernels. Returns false for rays that cannot hit
// anything, answered "miss" as the Embree backend does: NaN or infinite origin
// or direction, zero direction, NaN or empty interval. A negative tmin counts
// as 0 (as in the Embree backend).
bool prepare(const Ray& ray, RayQuery& q) {
  if (!is_finite(ray.origin) || !is_finite(ray.dir) || ray.dir == Vec3f(0.0f)) return false;
  if (!(ray.tmin < ray.tmax)) return false;  // also NaN
  q.tmin = ray.tmin > 0.0f ? ray.tmin : 0.0f;
  q.tmax = ray.tmax;
  if (!(q.tmin < q.tmax)) return false;
  for (int a = 0; a < 3; ++a) {
    q.org[a] = ray.origin[a];
    q.dir[a] = ray.dir[a];
  }
  set_ray_frame(ray.dir, q);
  return true;
}

Hit to_hit(const HitRecord& h) {
  Hit hit;
  hit.t = h.t;
  hit.shape = h.object;
  hit.prim = h.prim;
  hit.uv = {h.u, h.v};
  hit.instance = h.instance;
  return hit;
}

// The shapes of one group: those placed directly, or one prototype's.
struct Group {
  std::vector<uint32_t> meshes;  // non-empty meshes: a bottom level each
  std::vector<AnalyticPrim> analytic;  // every analytic shape: one bottom level
  std::vector<Bounds3f> analytic_boxes;
  std::size_t first_blas = 0, blas_count = 0;  // its bottom levels in blas_
};

class BvhAccelerator final : public Accelerator {
 public:
  bool build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag, const Options& options);

  bool intersect(const Ray& ray, Hit& hit) const override {
    RayQuery q;
    HitRecord h;
    if (!prepare(ray, q) || !kernels_.intersect(scene_, q, h)) return false;
    hit = to_hit(h);
    return true;
  }

  bool occluded(const Ray& ray) const override {
    RayQuery q;
    return prepare(ray, q) && kernels_.occluded(scene_, q);
  }

  bool counts_traversal() const override { return true; }

  bool intersect_counted(const Ray& ray, Hit& hit, TraversalCounters& counters) const override {
    RayQuery q;
    if (!prepare(ray, q)) return false;
    HitRecord h;
    Counters c{0, 0};
    const bool found = kernels_.intersect_counted(scene_, q, h, c);
    counters.nodes += c.nodes;
    counters.primitives += c.prims;
    if (found) hit = to_hit(h);
    return found;
  }

  Bounds3f bounds() const override { return bounds_; }
  AccelStats stats() const override { return stats_; }
  const SceneTreeStats& tree_stats() const { return tree_stats_; }
  uint64_t fingerprint() const;

 private:
  void build_bottom_levels(const SceneGeometry& geometry, std::vector<Group>& groups,
                           const BuildSettings& settings);
  void place(const SceneGeometry& geometry, const std::vector<Group>& groups, const CutoutTest* cutouts);

  std::vector<Blas> blas_;
  std::vector<BlasData> views_;  // the top level's items
  std::vector<Bounds3f> boxes_;  // their world bounds, while building
  TopLevel top_;
  SceneData scene_{nullptr, kEmptyRef, nullptr, 0, 0, nullptr};
  KernelTable kernels_{};
  Bounds3f bounds_;
  AccelStats stats_;
  SceneTreeStats tree_stats_;
};

// FNV-1a, 64 bits.
class Fnv1a {
 public:
  void add(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ull;
  }
  template <class V>
  void add_all(const V& v) {
    add(v.data(), v.size() * sizeof(v[0]));
  }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

uint64_t BvhAccelerator::fingerprint() const {
  Fnv1a h;
  h.add_all(top_.nodes);
  h.add(&top_.root, sizeof(top_.root));
  for (const Blas& b : blas_) {
    h.add_all(b.nodes);
    h.add_all(b.blocks);
    for (const AnalyticPrim& p : b.prims) {
      const auto type = static_cast<uint32_t>(p.shape.index());  // the alternative of Shape
      h.add(&type, sizeof(type));
      h.add(&p.object, sizeof(p.object));
    }
    h.add(&b.root, sizeof(b.root));
    h.add(&b.object, sizeof(b.object));
  }
  for (const BlasData& v : views_) h.add(&v.instance, sizeof(v.instance));
  return h.value();
}

bool choose_kernels(Isa isa, KernelTable& out, Diagnostics& diag) {
  const bool avx2 = cpu_has_avx2_fma(), avx512 = cpu_has_avx512();
  if (isa == Isa::Avx2 && !avx2) {
    diag.error(SourceLocation{}, "bvh: the AVX2 kernel was requested but this CPU lacks AVX2 or FMA");
    return false;
  }
  if (isa == Isa::Avx512 && !avx512) {
    diag.error(SourceLocation{}, "bvh: the AVX-512 kernel was requested but this CPU lacks AVX-512 F/VL/DQ/BW");
    return false;
  }
  if (isa == Isa::Sse2 || !avx2) {
    out = sse2_kernels();
  } else if (isa == Isa::Avx2 || !avx512) {
    out = avx2_kernels();
  } else {
    out = avx512_kernels();
  }
  return true;
}

// Sizes the layout cannot encode (layout.h: 27-bit item indices).
bool check_sizes(const SceneGeometry& geometry, Diagnostics& diag) {
  bool ok = true;
  for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
    const uint32_t n = primitive_count(geometry.shapes[i]);
    if (n >= kMaxItems) {
      diag.error(SourceLocation{}, "shape " + std::to_string(i) + " (triangle mesh): " + std::to_string(n) +
                                       " triangles; the bvh backend takes at most " + std::to_string(kMaxItems - 1) +
                                       " per mesh");
      ok = false;
    }
  }
  if (geometry.shapes.size() >= kMaxItems) {
    diag.error(SourceLocation{}, std::to_string(geometry.shapes.size()) + " shapes; the bvh backend takes at most " +
                                     std::to_string(kMaxItems - 1));
    ok = false;
  }
  return ok;
}

void add_to_group(const SceneGeometry& geometry, uint32_t object, Group& g) {
  std::visit(
      [&](const auto& shape) {
        if constexpr (WholeShape<std::decay_t<decltype(shape)>>) {
          g.analytic.push_back(AnalyticPrim{ShapeRef(&shape), object});
          g.analytic_boxes.push_back(pt::bounds(shape));
        } else if (primitive_count(shape) > 0) {
          g.meshes.push_back(object);
        }
      },
      geometry.shapes[object]);
}

// Group 0: the shapes placed directly; group 1 + p: prototype p.
std::vector<Group> make_groups(const SceneGeometry& geometry) {
  std::vector<Group> groups(1 + geometry.prototypes.size());
  const std::vector<bool> direct = placed_directly(geometry);
  for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
    if (direct[i]) add_to_group(geometry, static_cast<uint32_t>(i), groups[0]);
  }
  for (std::size_t p = 0; p < geometry.prototypes.size(); ++p) {
    for (uint32_t s : geometry.prototypes[p]) add_to_group(geometry, s, groups[1 + p]);
  }
  std::size_t next = 0;
  for (Group& g : groups) {
    g.first_blas = next;
    g.blas_count = g.meshes.size() + (g.analytic.empty() ? 0 : 1);
    next += g.blas_count;
  }
  return groups;
}

void BvhAccelerator::build_bottom_levels(const SceneGeometry& geometry, std::vector<Group>& groups,
                                         const BuildSettings& settings) {
  blas_.resize(groups.empty() ? 0 : groups.back().first_blas + groups.back().blas_count);
  for (Group& g : groups) {
    tbb::parallel_for(std::size_t{0}, g.meshes.size(), [&](std::size_t k) {
      blas_[g.first_blas + k] =
          build_mesh_blas(std::get<TriangleMesh>(geometry.shapes[g.meshes[k]]), g.meshes[k], settings);
    });
    if (!g.analytic.empty()) {
      blas_[g.first_blas + g.meshes.size()] = build_analytic_blas(std::move(g.analytic), g.analytic_boxes, settings);
    }
  }
}

// Whether a shape of bottom level `b` may be cut out when placed by `instance`.
uint16_t may_cut(const Blas& b, const CutoutTest* cutouts, uint32_t instance) {
  if (cutouts == nullptr) return 0;
  if (b.kind == BlasKind::Triangles) return cutouts->may_cut(b.object, instance) ? 1 : 0;
  for (const AnalyticPrim& p : b.prims) {
    if (cutouts->may_cut(p.object, instance)) return 1;
  }
  return 0;
}

// The top level's items: each bottom level placed directly, then each
// instance's placement of its prototype's bottom levels.
void BvhAccelerator::place(const SceneGeometry& geometry, const std::vector<Group>& groups,
                           const CutoutTest* cutouts) {
  std::size_t count = groups[0].blas_count;
  for (const Instance& inst : geometry.instances) count += groups[1 + inst.prototype].blas_count;
  views_.reserve(count);
  boxes_.reserve(count);
  for (std::size_t b = 0; b < groups[0].blas_count; ++b) {
    views_.push_back(blas_[b].view());
    views_.back().cutout = may_cut(blas_[b], cutouts, kNoInstance);
    boxes_.push_back(blas_[b].bounds);
  }
  for (std::size_t i = 0; i < geometry.instances.size(); ++i) {
    const Instance& inst = geometry.instances[i];
    const Group& g = groups[1 + inst.prototype];
    for (std::size_t b = g.first_blas; b < g.first_blas + g.blas_count; ++b) {
      BlasData v = blas_[b].view();
      v.instance = static_cast<uint32_t>(i);
      v.transform = &inst.transform;
      v.cutout = may_cut(blas_[b], cutouts, static_cast<uint32_t>(i));
      views_.push_back(v);
      boxes_.push_back(inst.transform.bounds(blas_[b].bounds));
    }
  }
  bounds_ = world_bounds(geometry);
}

bool BvhAccelerator::build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag,
                           const Options& options) {
  assert(geometry_usable(geometry));
  if (!check_sizes(geometry, diag)) return false;
  if (!choose_kernels(options.isa, kernels_, diag)) return false;

  // One bottom level per non-empty mesh, one over every analytic shape, for
  // the shapes placed directly and for each prototype.
  std::vector<Group> groups = make_groups(geometry);
  std::size_t primitives = 0;
  for (const Shape& s : geometry.shapes) primitives += primitive_count(s);

  const auto start = std::chrono::steady_clock::now();
  bool placed = false;
  pool.run([&] {
    build_bottom_levels(geometry, groups, options.build);
    place(geometry, groups, options.cutouts);
    placed = views_.size() > 1 || !geometry.instances.empty();
    if (placed && views_.size() >= kMaxItems) return;
    if (placed) top_ = build_top_level(boxes_, options.build);
  });
  const auto stop = std::chrono::steady_clock::now();
  if (views_.size() >= kMaxItems) {
    diag.error(SourceLocation{}, std::to_string(views_.size()) + " placed bottom levels; the bvh backend takes at most " +
                                     std::to_string(kMaxItems - 1));
    return false;
  }
  boxes_.clear();
  boxes_.shrink_to_fit();

  for (const Blas& b : blas_) tree_stats_.bottom.add(b.stats);
  const auto instanced = static_cast<uint32_t>(views_.size() - groups[0].blas_count);
  bool cut = false;
  for (const BlasData& v : views_) cut = cut || v.cutout != 0;
  const CutoutTest* cutouts = cut ? options.cutouts : nullptr;
  scene_ = SceneData{top_.nodes.data(), top_.root,          views_.data(), static_cast<uint32_t>(views_.size()),
                     instanced + (cut ? 1u : 0u), cutouts};
  tree_stats_.top = top_.stats;
  tree_stats_.bottom_levels = blas_.size();
  tree_stats_.isa = kernels_.isa;

  stats_.backend = std::string("bvh (8-wide binned SAH, ") + kernels_.isa + ")";
  stats_.build_seconds = std::chrono::duration<double>(stop - start).count();
  stats_.memory_bytes = tree_stats_.bottom.bytes + tree_stats_.top.bytes + views_.size() * sizeof(BlasData);
  stats_.primitive_count = primitives;
  return true;
}

}  // namespace

std::unique_ptr<Accelerator> build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag,
                                   const Options& options) {
  auto accel = std::make_unique<BvhAccelerator>();
  if (!accel->build(geometry, pool, diag, options)) return nullptr;
  return accel;
}

uint64_t layout_fingerprint(const Accelerator& accel) {
  const auto* bvh = dynamic_cast<const BvhAccelerator*>(&accel);
  return bvh != nullptr ? bvh->fingerprint() : 0;
}

const SceneTreeStats* tree_stats(const Accelerator& accel) {
  const auto* bvh = dynamic_cast<const BvhAccelerator*>(&accel);
  return bvh != nullptr ? &bvh->tree_stats() : nullptr;
}

}  // namespace pt::bvh

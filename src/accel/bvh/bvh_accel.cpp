#include "accel/bvh/bvh_accel.h"

#include <cassert>
#include <chrono>
#include <cmath>
#include <type_traits>
#include <variant>

#include <tbb/parallel_for.h>

#include "accel/bvh/kernels.h"
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
    q.rdir[a] = 1.0f / ray.dir[a];  // +-inf for +-0: the sign picks the entry plane below
    q.near[a] = std::signbit(ray.dir[a]) ? 1u : 0u;
  }
  // The ray frame of the watertight triangle test, computed exactly as
  // intersect_triangle() computes it (geometry/triangle.cpp).
  const int kz = fp::max_dimension(abs(ray.dir));
  const int kx = kz == 2 ? 0 : kz + 1;
  const int ky = kx == 2 ? 0 : kx + 1;
  const Vec3f d = fp::permute(ray.dir, kx, ky, kz);
  q.kx = static_cast<uint32_t>(kx);
  q.ky = static_cast<uint32_t>(ky);
  q.kz = static_cast<uint32_t>(kz);
  q.sz = 1.0f / d.z;
  q.sx = -d.x * q.sz;
  q.sy = -d.y * q.sz;
  return true;
}

Hit to_hit(const HitRecord& h) {
  Hit hit;
  hit.t = h.t;
  hit.shape = h.object;
  hit.prim = h.prim;
  hit.uv = {h.u, h.v};
  return hit;
}

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
  std::vector<Blas> blas_;
  std::vector<BlasData> views_;
  TopLevel top_;
  SceneData scene_{nullptr, kEmptyRef, nullptr, 0};
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
  template <class T>
  void add_all(const std::vector<T>& v) {
    add(v.data(), v.size() * sizeof(T));
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
  return h.value();
}

bool choose_kernels(Isa isa, KernelTable& out, Diagnostics& diag) {
  const bool avx2 = cpu_has_avx2_fma();
  if (isa == Isa::Avx2 && !avx2) {
    diag.error(SourceLocation{}, "bvh: the AVX2 kernel was requested but this CPU lacks AVX2 or FMA");
    return false;
  }
  out = (isa == Isa::Sse2 || !avx2) ? sse2_kernels() : avx2_kernels();
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

bool BvhAccelerator::build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag,
                           const Options& options) {
  assert(geometry_usable(geometry));
  if (!check_sizes(geometry, diag)) return false;
  if (!choose_kernels(options.isa, kernels_, diag)) return false;

  // One bottom level per non-empty mesh, one over every analytic shape.
  std::vector<uint32_t> meshes;
  std::vector<AnalyticPrim> analytic;
  std::vector<Bounds3f> analytic_boxes;
  std::size_t primitives = 0;
  for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
    const auto object = static_cast<uint32_t>(i);
    std::visit(
        [&](const auto& shape) {
          primitives += primitive_count(shape);
          if constexpr (WholeShape<std::decay_t<decltype(shape)>>) {
            analytic.push_back(AnalyticPrim{ShapeRef(&shape), object});
            analytic_boxes.push_back(pt::bounds(shape));
          } else if (primitive_count(shape) > 0) {
            meshes.push_back(object);
          }
        },
        geometry.shapes[i]);
    bounds_.extend(pt::bounds(geometry.shapes[i]));
  }

  const auto start = std::chrono::steady_clock::now();
  pool.run([&] {
    blas_.resize(meshes.size() + (analytic.empty() ? 0 : 1));
    tbb::parallel_for(std::size_t{0}, meshes.size(), [&](std::size_t k) {
      blas_[k] = build_mesh_blas(std::get<TriangleMesh>(geometry.shapes[meshes[k]]), meshes[k], options.build);
    });
    if (!analytic.empty()) blas_.back() = build_analytic_blas(std::move(analytic), analytic_boxes, options.build);
    if (blas_.size() > 1) {
      std::vector<Bounds3f> boxes;
      boxes.reserve(blas_.size());
      for (const Blas& b : blas_) boxes.push_back(b.bounds);
      top_ = build_top_level(boxes, options.build);
    }
  });
  const auto stop = std::chrono::steady_clock::now();

  views_.reserve(blas_.size());
  for (const Blas& b : blas_) {
    views_.push_back(b.view());
    tree_stats_.bottom.add(b.stats);
  }
  scene_ = SceneData{top_.nodes.data(), top_.root, views_.data(), static_cast<uint32_t>(views_.size())};
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

#include "accel/unbounded.h"

#include <cstdint>
#include <utility>
#include <variant>
#include <vector>

namespace pt {
namespace {

class UnboundedShapes final : public Accelerator {
 public:
  struct Plane {
    const InfinitePlane* plane;
    uint32_t object;
  };

  UnboundedShapes(std::unique_ptr<Accelerator> backend, std::vector<Plane> planes, const CutoutTest* cutouts)
      : backend_(std::move(backend)), planes_(std::move(planes)), cutouts_(cutouts) {}

  // The nearest plane first, then the backend for anything nearer.
  bool intersect(const Ray& ray, Hit& hit) const override {
    Ray r = ray;
    const bool plane = nearest_plane(r, hit);
    return backend_->intersect(r, hit) || plane;
  }
  bool occluded(const Ray& ray) const override {
    PrimHit h;
    for (const Plane& p : planes_) {
      if (hit_plane(p, ray, h)) return true;
    }
    return backend_->occluded(ray);
  }
  Bounds3f bounds() const override { return backend_->bounds(); }
  AccelStats stats() const override { return backend_->stats(); }
  bool counts_traversal() const override { return backend_->counts_traversal(); }
  bool intersect_counted(const Ray& ray, Hit& hit, TraversalCounters& counters) const override {
    Ray r = ray;
    const bool plane = nearest_plane(r, hit);
    counters.primitives += static_cast<uint32_t>(planes_.size());
    return backend_->intersect_counted(r, hit, counters) || plane;
  }

 private:
  // Shortens r.tmax to the nearest plane hit, which goes into `hit`.
  bool nearest_plane(Ray& r, Hit& hit) const {
    bool found = false;
    PrimHit h;
    for (const Plane& p : planes_) {
      if (!hit_plane(p, r, h)) continue;
      r.tmax = h.t;
      hit = Hit{h.t, p.object, 0, h.uv};
      found = true;
    }
    return found;
  }

  // A plane is never instanced: its transform is applied at import.
  bool hit_plane(const Plane& p, const Ray& r, PrimHit& h) const {
    if (cutouts_ != nullptr) return intersect_kept(*p.plane, 0, r, h, *cutouts_, p.object, kNoInstance);
    return pt::intersect(*p.plane, 0, r, h);
  }

  std::unique_ptr<Accelerator> backend_;
  std::vector<Plane> planes_;
  const CutoutTest* cutouts_;
};

}  // namespace

std::unique_ptr<Accelerator> with_unbounded_shapes(std::unique_ptr<Accelerator> backend,
                                                   const SceneGeometry& geometry, const CutoutTest* cutouts) {
  std::vector<UnboundedShapes::Plane> planes;
  for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
    if (const auto* p = std::get_if<InfinitePlane>(&geometry.shapes[i])) {
      planes.push_back({p, static_cast<uint32_t>(i)});
    }
  }
  if (planes.empty() || backend == nullptr) return backend;
  return std::make_unique<UnboundedShapes>(std::move(backend), std::move(planes), cutouts);
}

}  // namespace pt

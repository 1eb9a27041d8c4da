// The one narrow interface between the renderer and its ray-tracing backends.
// Backends: "embree" (Embree 3: triangle geometry for meshes, user geometry
// calling src/geometry for analytic shapes) and "bvh" (our own two-level SAH
// BVH, docs/bvh.md). Both return the same hit record.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "accel/cutout.h"
#include "core/diagnostics.h"
#include "core/math.h"
#include "geometry/shapes.h"

namespace pt {

class WorkerPool;

enum class AccelKind { Embree, Bvh };

// Parses "embree" / "bvh"; returns false for anything else.
bool parse_accel_kind(const std::string& name, AccelKind& out);
const char* accel_kind_name(AccelKind kind);
// Names accepted by parse_accel_kind, for help texts and error messages.
std::vector<std::string> accel_kind_names();

struct Hit {
  float t = kInfinity;
  uint32_t shape = UINT32_MAX;  // object id: index into SceneGeometry::shapes
  uint32_t prim = 0;            // triangle index within a mesh, else 0
  Vec2f uv;                     // as PrimHit::uv
  // The instance through which the shape was hit (SceneGeometry::instances),
  // or kNoInstance for a shape placed directly; `t` is the world ray's parameter.
  uint32_t instance = kNoInstance;
};

struct AccelStats {
  std::string backend;          // "embree 3.13.5 (AVX2)" etc.
  double build_seconds = 0;
  std::size_t memory_bytes = 0; // acceleration-structure memory, best estimate
  std::size_t build_peak_bytes = 0; // the most the build held at once (Embree's monitor; 0: not known)
  std::size_t primitive_count = 0;
};

// The work one query did, for the traversal-cost view ("bvh-cost").
struct TraversalCounters {
  uint32_t nodes = 0;       // acceleration-structure nodes whose children were tested
  uint32_t primitives = 0;  // primitive intersection tests
};

class Accelerator {
 public:
  virtual ~Accelerator() = default;
  // Nearest hit with ray.tmin < t < ray.tmax. Thread-safe.
  virtual bool intersect(const Ray& ray, Hit& hit) const = 0;
  // Any hit with ray.tmin < t < ray.tmax. Thread-safe.
  virtual bool occluded(const Ray& ray) const = 0;
  virtual Bounds3f bounds() const = 0;
  virtual AccelStats stats() const = 0;

  // True if intersect_counted() counts its work (our BVH; Embree cannot).
  virtual bool counts_traversal() const { return false; }
  // As intersect(), adding the work done to `counters` where the backend
  // counts_traversal(); other backends leave `counters` unchanged.
  virtual bool intersect_counted(const Ray& ray, Hit& hit, TraversalCounters& counters) const {
    (void)counters;
    return intersect(ray, hit);
  }
};

// Whether every shape passes the part of its validation rule that the backends
// rely on (finite values, mesh indices in range: the `unusable` problems of
// geometry/shape_base.h). The backends assert it in debug builds; scene
// validation (src/scene/validate.h) refuses such shapes before they get here.
bool geometry_usable(const SceneGeometry& geometry);

// Builds the chosen backend over `geometry`, which must outlive the accelerator,
// as must `cutouts` (the scene's alpha cutouts, accel/cutout.h; null for none).
// The build runs inside `pool`'s arena. On failure (invalid geometry, an Embree
// device error) returns nullptr and reports to `diag`.
std::unique_ptr<Accelerator> build_accelerator(AccelKind kind, const SceneGeometry& geometry,
                                               WorkerPool& pool, Diagnostics& diag,
                                               const CutoutTest* cutouts = nullptr);

}  // namespace pt

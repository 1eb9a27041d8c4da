// The benchmark's yardstick, "bare Embree": Embree used directly, as an
// application with no contract of its own would use it. Meshes are Embree's own
// triangle geometry (RTC_GEOMETRY_TYPE_TRIANGLE over the mesh's buffers, no
// other preparation), analytic shapes the Embree backend's user geometry (Embree
// has nothing else for them), transforms Embree instances; scene flag
// RTC_SCENE_FLAG_ROBUST, build quality HIGH, as the backend. A query copies the
// ray into an RTCRayHit (tnear = max(tmin, FLT_MIN), tfar = tmax) and calls
// rtcIntersect1 / rtcOccluded1: none of the backend's checks of invalid rays,
// conversion of the open interval, or removal of degenerate triangles.
// Not a renderer backend: its hit records are Embree's as they come.
#pragma once

#include <embree3/rtcore.h>
#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "accel/accelerator.h"
#include "accel/embree/embree_device.h"
#include "accel/embree/queries.h"

namespace pt::bench {

class BareEmbree final : public Accelerator {
 public:
  BareEmbree() = default;
  ~BareEmbree() override;
  BareEmbree(const BareEmbree&) = delete;
  BareEmbree& operator=(const BareEmbree&) = delete;

  // False with `diag` on failure.
  bool build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag);

  // The backend's query and read-back (accel/embree/queries.h) on the ray as it is.
  bool intersect(const Ray& ray, Hit& hit) const override {
    RTCRayHit rh;
    set(ray, rh.ray);
    return embree::intersect1(scene_, rh, instance_base_, hit);
  }

  bool occluded(const Ray& ray) const override {
    RTCRay r;
    set(ray, r);
    return embree::occluded1(scene_, r);
  }

  Bounds3f bounds() const override { return bounds_; }
  AccelStats stats() const override { return stats_; }

 private:
  // Written as Embree reads it (store_ray; filled field by field, the
  // yardstick was 5-25% slower than Embree is on camera rays,
  // docs/bench/embree-wrapper.md). tnear is at least the smallest normal
  // float, the query the backend asks for rays with tmin <= 0 (tnear = 0 cost
  // Embree time on shadow and diffuse rays starting on a surface).
  static void set(const Ray& ray, RTCRay& r) {
    const float tnear = std::max(ray.tmin, std::numeric_limits<float>::min());
    embree::store_ray(r, _mm_setr_ps(ray.origin.x, ray.origin.y, ray.origin.z, tnear),
                      _mm_setr_ps(ray.dir.x, ray.dir.y, ray.dir.z, 0.0f), std::bit_cast<uint32_t>(ray.tmax));
  }
  RTCScene new_scene() const;
  bool attach(RTCScene scene, const SceneGeometry& geometry, uint32_t object);

  embree::Device device_;  // destroyed after the scenes
  RTCScene scene_ = nullptr;
  std::vector<RTCScene> prototypes_;
  uint32_t instance_base_ = 0;
  Bounds3f bounds_;
  AccelStats stats_;
};

// Returns nullptr and reports to `diag` on failure.
std::unique_ptr<BareEmbree> build_embree_reference(const SceneGeometry& geometry, WorkerPool& pool,
                                                   Diagnostics& diag);

}  // namespace pt::bench

// The benchmark's yardstick, "bare Embree": Embree used directly, as an
// application with no contract of its own would use it. Meshes are Embree's own
// triangle geometry (RTC_GEOMETRY_TYPE_TRIANGLE over the mesh's buffers, no
// other preparation), analytic shapes the Embree backend's user geometry (Embree
// has nothing else for them), transforms Embree instances; scene flag
// RTC_SCENE_FLAG_ROBUST, build quality HIGH, as the backend. A query copies the
// ray into an RTCRayHit (tnear = max(tmin, 0), tfar = tmax) and calls
// rtcIntersect1 / rtcOccluded1: none of the backend's checks of invalid rays,
// conversion of the open interval, or removal of degenerate triangles.
// Not a renderer backend: its hit records are Embree's as they come.
#pragma once

#include <embree3/rtcore.h>

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
  static void set(const Ray& ray, RTCRay& r) {
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.dir_x = ray.dir.x;
    r.dir_y = ray.dir.y;
    r.dir_z = ray.dir.z;
    r.tnear = ray.tmin > 0.0f ? ray.tmin : 0.0f;
    r.tfar = ray.tmax;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
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

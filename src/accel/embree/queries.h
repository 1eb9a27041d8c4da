// One ray through an Embree scene and its answer read back as our Hit: the
// query every user of Embree's scenes makes (the Embree backend, and the
// benchmark's bare-Embree yardstick, tools/bench/accel/embree_reference.h),
// once. The caller fills the RTCRay (the backend converts the open interval
// and refuses rays Embree cannot take; the yardstick copies the ray as it is).
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>

#include "accel/accelerator.h"

namespace pt::embree {

// Intersects `rh.ray` (set by the caller) with `scene`; on a hit fills `hit`
// (t, the shape = geomID, the triangle = primID, barycentrics, and the instance:
// instID - `instance_base`, or kNoInstance for a shape placed directly).
inline bool intersect1(RTCScene scene, RTCRayHit& rh, uint32_t instance_base, Hit& hit) {
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.t = rh.ray.tfar;
  hit.shape = rh.hit.geomID;
  hit.prim = rh.hit.primID;
  hit.uv = {rh.hit.u, rh.hit.v};
  hit.instance = rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID ? kNoInstance : rh.hit.instID[0] - instance_base;
  return true;
}

// Whether anything blocks `ray` (set by the caller) in `scene`: Embree sets
// tfar to -infinity when it finds a blocker.
inline bool occluded1(RTCScene scene, RTCRay& ray) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar == -kInfinity;
}

}  // namespace pt::embree

// One ray through an Embree scene and its answer read back as our Hit: the
// query every user of Embree's scenes makes (the Embree backend, and the
// benchmark's bare-Embree yardstick, tools/bench/accel/embree_reference.h),
// once, and the writing of its ray (store_ray). The caller chooses the ray's
// values (the backend converts the open interval and refuses rays Embree
// cannot take; the yardstick copies the ray as it is).
#pragma once

#include <embree3/rtcore.h>
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "accel/accelerator.h"

namespace pt::embree {

// Writes an RTCRay as Embree reads it: three 16-byte stores, (org, tnear),
// (dir, time = 0) and (tfar, mask = all, id = 0, flags = 0). Embree loads
// (org, tnear) and (dir, time) as 16-byte vectors, and a load that spans
// several smaller stores cannot take its data from the store buffer: it waits
// until they reach the cache (5-26% of camera rays' throughput,
// docs/bench/embree-wrapper.md). `org_tnear` holds tnear in lane 3, `dir`'s
// lane 3 is ignored.
inline void store_ray(RTCRay& out, __m128 org_tnear, __m128 dir, uint32_t tfar_bits) {
  static_assert(offsetof(RTCRay, tnear) == 12 && offsetof(RTCRay, dir_x) == 16 && offsetof(RTCRay, time) == 28 &&
                offsetof(RTCRay, tfar) == 32 && offsetof(RTCRay, flags) == 44);
  const __m128 keep3 = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
  _mm_storeu_ps(&out.org_x, org_tnear);
  _mm_storeu_ps(&out.dir_x, _mm_and_ps(dir, keep3));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(&out.tfar), _mm_setr_epi32(static_cast<int>(tfar_bits), -1, 0, 0));
}

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

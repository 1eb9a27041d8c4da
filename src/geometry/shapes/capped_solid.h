// What the capped solids of revolution (cylinder.h, cone.h) share: the ray's
// interval inside the slab between the two cap planes, the choice of the hit
// from the overlap of that interval with the curved side's (entry = the later
// entry, exit = the earlier exit, so side and caps meet without a crack), and
// the reprojection of a hit point onto the axis frame. Parts are numbered
// 0 = side, 1 = cap at p0, 2 = cap at p1 (PrimHit::uv.x).
#pragma once

#include <cmath>
#include <utility>

#include "geometry/float_util.h"
#include "geometry/shape_base.h"

namespace pt::capped_detail {

enum Part { kSide = 0, kCap0 = 1, kCap1 = 2 };

// The slab 0 <= h <= len along the axis, for a ray whose origin is at height
// fa and whose direction has axial component da: [s_in, s_out] and the cap
// that bounds each end. False if the ray is parallel to the caps and outside
// the slab (or NaN).
struct Slab {
  float s_in = -kInfinity, s_out = kInfinity;
  Part cap_in = kCap0, cap_out = kCap1;
};
inline bool slab_interval(float fa, float da, float len, Slab& s) {
  if (da != 0.0f) {
    const float t0 = -fa / da;
    const float t1 = (len - fa) / da;
    if (da > 0.0f) {
      s.s_in = t0;
      s.s_out = t1;
    } else {
      s.s_in = t1;
      s.s_out = t0;
      std::swap(s.cap_in, s.cap_out);
    }
    return true;
  }
  return fa >= 0.0f && fa <= len;
}

// The nearest hit in (tmin, tmax) of the solid whose side interval is
// [c_in, c_out] and slab interval `s`: fills hit.t and the part.
inline bool pick_hit(float c_in, float c_out, const Slab& s, const Ray& ray, PrimHit& hit, Part& part) {
  const bool side_in = c_in > s.s_in;
  const bool side_out = c_out < s.s_out;
  const float t_enter = side_in ? c_in : s.s_in;
  const float t_exit = side_out ? c_out : s.s_out;
  if (!(t_enter <= t_exit)) return false;
  if (t_enter > ray.tmin && t_enter < ray.tmax) {
    hit.t = t_enter;
    part = side_in ? kSide : s.cap_in;
  } else if (t_exit > ray.tmin && t_exit < ray.tmax) {
    hit.t = t_exit;
    part = side_out ? kSide : s.cap_out;
  } else {
    return false;
  }
  return true;
}

// A hit point in the frame of the axis p0 -> p1: unit axis a, the
// deterministic frame (e0, e1) around it (texture u), the point q relative to
// p0, its height h along a, its distance rl from the axis and the unit radial
// direction (e0 on the axis).
struct AxisPoint {
  float len;
  Vec3f a, e0, e1, q;
  float h, rl;
  Vec3f dir;
};
inline AxisPoint axis_point(Vec3f p0, Vec3f p1, Vec3f p) {
  AxisPoint ap;
  const Vec3f axis = p1 - p0;
  ap.len = length(axis);
  ap.a = axis / ap.len;
  fp::axis_frame(ap.a, ap.e0, ap.e1);
  ap.q = p - p0;
  ap.h = dot(ap.q, ap.a);
  const Vec3f radial = ap.q - ap.a * ap.h;
  ap.rl = length(radial);
  ap.dir = (ap.rl > 0.0f && std::isfinite(ap.rl)) ? radial / ap.rl : ap.e0;
  return ap;
}

}  // namespace pt::capped_detail

// The capped cylinder between cap centres p0 and p1: its data and every
// routine that follows from it. The solid is the intersection of an infinite
// cylinder and the slab between the two cap planes; the ray's interval inside
// it is the overlap of the two intervals (like a ray/box slab test), so side
// and caps meet without a crack at the rims, and a ray starting inside finds
// its exit.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "geometry/float_util.h"
#include "geometry/shape_base.h"
#include "geometry/shapes/capped_solid.h"

namespace pt {

// Capped cylinder between cap centres p0 and p1.
struct Cylinder {
  Vec3f p0, p1;
  float radius = 1;
};

inline Bounds3f bounds(const Cylinder& c) {
  Bounds3f b;
  const Vec3f axis = c.p1 - c.p0;
  const float len = length(axis);
  const float r = c.radius > 0.0f ? c.radius : 0.0f;
  Vec3f ext(r);
  if (len > 0.0f && std::isfinite(len)) ext = fp::circle_extent(axis / len, r);  // each cap
  b.extend(min(c.p0, c.p1) - ext);
  b.extend(max(c.p0, c.p1) + ext);
  return fp::pad(b);
}

inline bool intersect(const Cylinder& cyl, const Ray& ray, PrimHit& hit) {
  const float r = cyl.radius;
  const float len = length(cyl.p1 - cyl.p0);
  if (!(r > 0.0f) || !(len > 0.0f) || !std::isfinite(len)) return false;
  const Vec3f a = (cyl.p1 - cyl.p0) / len;
  const Vec3f f = ray.origin - cyl.p0;
  const Vec3f d = ray.dir;
  const float fa = dot(f, a);
  const float da = dot(d, a);

  // Interval inside the slab 0 <= h <= len, and which cap bounds each end.
  capped_detail::Slab slab;
  if (!capped_detail::slab_interval(fa, da, len, slab)) return false;

  // Interval inside the infinite cylinder: the stable quadratic of the sphere
  // applied to the components perpendicular to the axis.
  const Vec3f fp = f - a * fa;
  const Vec3f dp = d - a * da;
  const float qa = dot(dp, dp);
  const double c = static_cast<double>(fp.x) * fp.x + static_cast<double>(fp.y) * fp.y +
                   static_cast<double>(fp.z) * fp.z - static_cast<double>(r) * r;  // see sphere.cpp
  float c_in = -kInfinity, c_out = kInfinity;
  if (qa > 0.0f) {
    const float qb = dot(fp, dp);
    const float len_l = length(fp - (qb / qa) * dp);
    const float disc = qa * ((r + len_l) * (r - len_l));
    if (!(disc >= 0.0f)) return false;
    const float q = -(qb + std::copysign(std::sqrt(disc), qb));
    c_in = static_cast<float>(c / q);
    c_out = q / qa;
    if (c_in > c_out) std::swap(c_in, c_out);
  } else if (!(c < 0.0)) {
    return false;  // parallel to the axis and outside the cylinder (or NaN)
  }

  capped_detail::Part part;
  if (!capped_detail::pick_hit(c_in, c_out, slab, ray, hit, part)) return false;
  hit.uv = {static_cast<float>(part), 0.0f};
  return true;
}

inline SurfaceGeometry surface(const Cylinder& cyl, const Ray& ray, const PrimHit& hit) {
  // Reproject the ray's point onto the part it hit.
  const capped_detail::AxisPoint ap = capped_detail::axis_point(cyl.p0, cyl.p1, ray.at(hit.t));
  const float len = ap.len, h = ap.h, rl = ap.rl;
  const Vec3f a = ap.a, e0 = ap.e0, e1 = ap.e1, dir = ap.dir;

  SurfaceGeometry sg;
  const int part = static_cast<int>(hit.uv.x);
  float v;
  if (part == capped_detail::kSide) {
    const float hc = std::clamp(h, 0.0f, len);
    sg.p = cyl.p0 + a * hc + dir * cyl.radius;
    sg.ng = dir;
    v = hc / len;
  } else {
    const float rc = std::min(rl, cyl.radius);
    sg.p = (part == capped_detail::kCap0 ? cyl.p0 : cyl.p1) + dir * rc;
    sg.ng = part == capped_detail::kCap0 ? -a : a;
    v = part == capped_detail::kCap0 ? 0.0f : 1.0f;
  }
  sg.ns = sg.ng;
  sg.uv = {fp::longitude_fraction(dot(dir, e0), dot(dir, e1)), v};
  sg.p_error = fp::gamma(8) * (abs(sg.p) + abs(cyl.p0) + Vec3f(len + cyl.radius));
  return sg;
}

// u is the longitude about the axis; v runs along the side (constant on the caps).
inline UvDerivatives uv_derivatives(const Cylinder& cyl, const SurfaceGeometry& sg) {
  const Vec3f axis = cyl.p1 - cyl.p0;
  const float len = length(axis);
  if (!(len > 0.0f)) return {};
  const Vec3f a = axis / len;
  const Vec3f radial = (sg.p - cyl.p0) - a * dot(sg.p - cyl.p0, a);
  const bool cap = std::fabs(dot(sg.ng, a)) > 0.5f;
  return {cross(a, radial) * (2.0f * kPi), cap ? Vec3f(0.0f) : axis};
}

inline uint32_t primitive_count(const Cylinder&) { return 1; }

// Validation (fields as the native format names them).
inline void check(const Cylinder& cyl, ShapeChecker& c) {
  if (!is_finite(cyl.p0) || !is_finite(cyl.p1) || !std::isfinite(cyl.radius))
    c.unusable("", "cylinder has a non-finite end point or radius");
  if (!(cyl.radius > 0.0f)) c.error("radius", "radius must be > 0, got " + format_number(cyl.radius));
  if (length(cyl.p1 - cyl.p0) == 0.0f) c.warning("", "cylinder has zero length; it will not be visible");
}

// Sampling by area: the side or a cap in proportion to its area.
struct CylinderAreaSampler {
  Cylinder cylinder;
  Distribution1D parts;  // side, cap at p0, cap at p1
  float area = 0.0f;

  void sample(Vec2f u, Vec3f& q, Vec3f& n) const {
    std::size_t part = 0;
    const Vec2f v = pick_part(parts, u, part);
    const Cylinder* c = &cylinder;
    const Vec3f axis = c->p1 - c->p0;
    const Frame frame = Frame::from_normal(normalize(axis));
    if (part == 0) {
      const float phi = 2.0f * kPi * v.y;
      n = frame.s * std::cos(phi) + frame.t * std::sin(phi);
      q = c->p0 + axis * v.x + n * c->radius;
    } else {
      const Vec2f d = sample_uniform_disk_concentric(v);
      const Vec3f centre = part == 1 ? c->p0 : c->p1;
      q = centre + (frame.s * d.x + frame.t * d.y) * c->radius;
      n = part == 1 ? -frame.n : frame.n;
    }
  }
};

inline CylinderAreaSampler make_area_sampler(const Cylinder& c) {
  const float h = length(c.p1 - c.p0), cap = kPi * c.radius * c.radius;
  const float side = 2.0f * kPi * c.radius * h;
  return {c, Distribution1D({side, cap, cap}), side + 2.0f * cap};
}

}  // namespace pt

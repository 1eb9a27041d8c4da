// The capped cone, pointed or truncated: base centre p0 with radius `radius`,
// top centre p1 with radius `top_radius` (0: the apex is p1). Its data and
// every routine that follows from it. The solid is convex: the intersection of
// the slab between the cap planes and the infinite (double) cone, whose
// quadratic is solved in double with the stable root formula; the ray's
// interval inside the solid is the overlap of the two intervals (as the
// cylinder's), so side and caps meet without a crack, and a ray starting
// inside finds its exit. Texture coordinates as pbrt-v4's cone: u = phi / 2pi
// about the axis (phi from fp::axis_frame's first axis), v = height / length
// on the side; the caps have v = 0 (base) and 1 (top), as the cylinder's.
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

struct Cone {
  Vec3f p0, p1;            // base and top centres
  float radius = 1;        // at p0
  float top_radius = 0;    // at p1; 0 for a pointed cone
};

namespace cone_detail {

// The interval of t where the ray is inside the infinite cone's nappe that
// holds the solid: r(t)^2 <= R(t)^2 with R(t) = g - kd t >= 0, where r is the
// distance from the axis. Quadratic A t^2 + 2 B t + C (double). False if empty.
inline bool nappe_interval(double A, double B, double C, double kd, float& lo, float& hi) {
  lo = -kInfinity;
  hi = kInfinity;
  if (A == 0.0) {  // parallel to a line of the cone: 2 B t + C <= 0
    if (B == 0.0) return C <= 0.0;
    const float t = static_cast<float>(-C / (2.0 * B));
    (B > 0.0 ? hi : lo) = t;
    return true;
  }
  const double disc = B * B - A * C;
  if (!(disc >= 0.0)) return A < 0.0 && C <= 0.0;  // A < 0 and no root: inside everywhere (or NaN: miss)
  const double q = -(B + std::copysign(std::sqrt(disc), B));
  float t0 = static_cast<float>(q / A);
  float t1 = q != 0.0 ? static_cast<float>(C / q) : t0;
  if (t0 > t1) std::swap(t0, t1);
  if (A > 0.0) {
    lo = t0;
    hi = t1;
  } else if (kd > 0.0) {  // two pieces; R decreases along the ray: the nappe is the first one
    hi = t0;
  } else {
    lo = t1;
  }
  return true;
}

}  // namespace cone_detail

inline Bounds3f bounds(const Cone& c) {
  Bounds3f b;
  const Vec3f axis = c.p1 - c.p0;
  const float len = length(axis);
  const float r = std::max({c.radius, c.top_radius, 0.0f});
  Vec3f ext(r);
  if (len > 0.0f && std::isfinite(len)) ext = fp::circle_extent(axis / len, r);  // the larger cap
  b.extend(min(c.p0, c.p1) - ext);
  b.extend(max(c.p0, c.p1) + ext);
  return fp::pad(b);
}

inline bool intersect(const Cone& cone, const Ray& ray, PrimHit& hit) {
  const float len = length(cone.p1 - cone.p0);
  if (!(cone.radius > 0.0f) || !(cone.top_radius >= 0.0f) || !(len > 0.0f) || !std::isfinite(len)) return false;
  const Vec3f a = (cone.p1 - cone.p0) / len;
  const Vec3f f = ray.origin - cone.p0;
  const float fa = dot(f, a), da = dot(ray.dir, a);

  // Interval inside the slab 0 <= h <= len, and which cap bounds each end.
  capped_detail::Slab slab;
  if (!capped_detail::slab_interval(fa, da, len, slab)) return false;

  // Radius R(h) = r0 - k h along the axis; along the ray R = g - k da t.
  const double k = (static_cast<double>(cone.radius) - cone.top_radius) / len;
  const double g = cone.radius - k * fa;
  const Vec3f fp = f - a * fa, dp = ray.dir - a * da;
  const double kd = k * da;
  const double A = static_cast<double>(dot(dp, dp)) - kd * kd;
  const double B = static_cast<double>(fp.x) * dp.x + static_cast<double>(fp.y) * dp.y +
                   static_cast<double>(fp.z) * dp.z + kd * g;
  const double C = static_cast<double>(fp.x) * fp.x + static_cast<double>(fp.y) * fp.y +
                   static_cast<double>(fp.z) * fp.z - g * g;
  float c_in, c_out;
  if (!cone_detail::nappe_interval(A, B, C, kd, c_in, c_out)) return false;

  capped_detail::Part part;
  if (!capped_detail::pick_hit(c_in, c_out, slab, ray, hit, part)) return false;
  if (part == capped_detail::kCap1 && !(cone.top_radius > 0.0f)) part = capped_detail::kSide;  // the apex
  hit.uv = {static_cast<float>(part), 0.0f};
  return true;
}

inline SurfaceGeometry surface(const Cone& cone, const Ray& ray, const PrimHit& hit) {
  // Reproject the ray's point onto the part it hit.
  const capped_detail::AxisPoint ap = capped_detail::axis_point(cone.p0, cone.p1, ray.at(hit.t));
  const float len = ap.len, rl = ap.rl;
  const Vec3f a = ap.a, q = ap.q, dir = ap.dir;
  const float k = (cone.radius - cone.top_radius) / len;

  SurfaceGeometry sg;
  const int part = static_cast<int>(hit.uv.x);
  float v;
  if (part == capped_detail::kSide) {
    // The side point nearest the hit along the slant (and the normal there).
    const float slant2 = len * len + (cone.radius - cone.top_radius) * (cone.radius - cone.top_radius);
    const Vec3f s = a * len + dir * (cone.top_radius - cone.radius);  // base rim -> top rim
    const float w = std::clamp(dot(q - dir * cone.radius, s) / slant2, 0.0f, 1.0f);
    const float hc = w * len;
    sg.p = cone.p0 + a * hc + dir * (cone.radius - k * hc);
    sg.ng = normalize(dir + a * k);
    v = w;
  } else {
    const float rmax = part == capped_detail::kCap0 ? cone.radius : cone.top_radius;
    sg.p = (part == capped_detail::kCap0 ? cone.p0 : cone.p1) + dir * std::min(rl, rmax);
    sg.ng = part == capped_detail::kCap0 ? -a : a;
    v = part == capped_detail::kCap0 ? 0.0f : 1.0f;
  }
  sg.ns = sg.ng;
  sg.uv = {fp::longitude_fraction(dot(dir, ap.e0), dot(dir, ap.e1)), v};
  sg.p_error = fp::gamma(8) * (abs(sg.p) + abs(cone.p0) + Vec3f(len + cone.radius));
  return sg;
}

// u is the longitude about the axis; v runs along the slant from the base rim
// to the top rim (constant on the caps).
inline UvDerivatives uv_derivatives(const Cone& cone, const SurfaceGeometry& sg) {
  const Vec3f axis = cone.p1 - cone.p0;
  const float len = length(axis);
  if (!(len > 0.0f)) return {};
  const Vec3f a = axis / len;
  const Vec3f radial = (sg.p - cone.p0) - a * dot(sg.p - cone.p0, a);
  const float r = length(radial);
  const Vec3f dir = r > 0.0f ? radial / r : Vec3f(0.0f);
  const bool cap = std::fabs(dot(sg.ng, a)) > 1.0f - 1e-6f;  // a cap's normal is the axis
  const Vec3f slant = axis + dir * (cone.top_radius - cone.radius);
  return {cross(a, radial) * (2.0f * kPi), cap ? Vec3f(0.0f) : slant};
}

inline uint32_t primitive_count(const Cone&) { return 1; }

// Validation (fields as the native format names them).
inline void check(const Cone& cone, ShapeChecker& c) {
  if (!is_finite(cone.p0) || !is_finite(cone.p1) || !std::isfinite(cone.radius) || !std::isfinite(cone.top_radius))
    c.unusable("", "cone has a non-finite end point or radius");
  if (!(cone.radius > 0.0f)) c.error("radius", "radius must be > 0, got " + format_number(cone.radius));
  if (!(cone.top_radius >= 0.0f))
    c.error("top_radius", "top_radius must be >= 0, got " + format_number(cone.top_radius));
  if (length(cone.p1 - cone.p0) == 0.0f) c.warning("", "cone has zero height; it will not be visible");
}

// Sampling by area: the side or a cap in proportion to its area. On the side,
// the fraction s of the way up the slant has density in proportion to the
// radius there, R(s) = r0 + (r1 - r0) s; inverted in a form without
// cancellation that is exact for the cylinder (r0 == r1: s = u).
struct ConeAreaSampler {
  Cone cone;
  Distribution1D parts;  // side, base cap, top cap
  float area = 0.0f;

  void sample(Vec2f u, Vec3f& q, Vec3f& n) const {
    std::size_t part = 0;
    const Vec2f v = pick_part(parts, u, part);
    const Vec3f axis = cone.p1 - cone.p0;
    const float len = length(axis);
    const Frame frame = Frame::from_normal(axis / len);
    const float r0 = cone.radius, r1 = cone.top_radius;
    if (part == 0) {
      const float s = v.x * (r0 + r1) / (r0 + std::sqrt(r0 * r0 + v.x * (r1 * r1 - r0 * r0)));
      const float phi = 2.0f * kPi * v.y;
      const Vec3f dir = frame.s * std::cos(phi) + frame.t * std::sin(phi);
      q = cone.p0 + axis * s + dir * (r0 + (r1 - r0) * s);
      n = normalize(dir + frame.n * ((r0 - r1) / len));
    } else {
      const Vec2f d = sample_uniform_disk_concentric(v);
      q = (part == 1 ? cone.p0 : cone.p1) + (frame.s * d.x + frame.t * d.y) * (part == 1 ? r0 : r1);
      n = part == 1 ? -frame.n : frame.n;
    }
  }
};

inline ConeAreaSampler make_area_sampler(const Cone& c) {
  const float len = length(c.p1 - c.p0);
  const float slant = std::sqrt(len * len + (c.radius - c.top_radius) * (c.radius - c.top_radius));
  const float side = kPi * (c.radius + c.top_radius) * slant;
  const float cap0 = kPi * c.radius * c.radius, cap1 = kPi * c.top_radius * c.top_radius;
  return {c, Distribution1D({side, cap0, cap1}), side + cap0 + cap1};
}

}  // namespace pt

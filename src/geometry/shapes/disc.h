// The disc (an annulus with an inner radius): its data and every routine that
// follows from it. Intersection: the plane's hit (in double) and the distance
// from the centre. Texture coordinates as pbrt-v4's disk: u = phi / 2pi about
// the normal (phi from the deterministic frame's first axis, fp::axis_frame),
// v = (radius - r) / (radius - inner_radius): 0 on the rim, 1 at the centre
// (or on the inner rim).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "geometry/float_util.h"
#include "geometry/shape_base.h"
#include "geometry/shapes/plane.h"

namespace pt {

struct Disc {
  Vec3f center;
  Vec3f normal{0, 1, 0};  // unit; the side the disc faces
  float radius = 1;
  float inner_radius = 0;  // 0: a full disc; else an annulus
};

// A disc as a scene file gives it: the normal scaled to unit length (a zero
// normal is kept for check() to report).
inline Disc make_disc(Vec3f center, Vec3f normal, float radius, float inner_radius) {
  const float ln = length(normal);
  return Disc{center, ln > 0.0f && std::isfinite(ln) ? normal / ln : normal, radius, inner_radius};
}

namespace disc_detail {

// Whether the ray point at t lies in the annulus inner <= |p - c| <= outer (in double).
inline bool in_annulus(Vec3f c, double t, const Ray& ray, float inner, float outer) {
  const double qx = ray.origin.x + t * ray.dir.x - c.x;
  const double qy = ray.origin.y + t * ray.dir.y - c.y;
  const double qz = ray.origin.z + t * ray.dir.z - c.z;
  const double r2 = qx * qx + qy * qy + qz * qz;
  return r2 <= static_cast<double>(outer) * outer && r2 >= static_cast<double>(inner) * inner;
}

}  // namespace disc_detail

inline Bounds3f bounds(const Disc& d) {
  const Vec3f e = fp::circle_extent(d.normal, d.radius);
  Bounds3f b;
  b.extend(d.center - e);
  b.extend(d.center + e);
  return fp::pad(b);
}

inline bool intersect(const Disc& d, const Ray& ray, PrimHit& hit) {
  if (!(d.radius > 0.0f) || !(d.inner_radius < d.radius)) return false;
  const double td = plane_detail::plane_t(d.center, d.normal, ray);
  const float t = static_cast<float>(td);
  if (!(t > ray.tmin && t < ray.tmax)) return false;
  if (!disc_detail::in_annulus(d.center, td, ray, d.inner_radius, d.radius)) return false;
  hit.t = t;
  hit.uv = {0.0f, 0.0f};
  return true;
}

inline SurfaceGeometry surface(const Disc& d, const Ray& ray, const PrimHit& hit) {
  SurfaceGeometry sg;
  const Vec3f q = plane_detail::project(d.center, d.normal, ray.at(hit.t)) - d.center;
  const float r = length(q);
  // Clamped into the annulus: the reprojected point may round just outside.
  const float rc = std::clamp(r, d.inner_radius, d.radius);
  Vec3f e0, e1;
  fp::axis_frame(d.normal, e0, e1);
  const Vec3f dir = (r > 0.0f && std::isfinite(r)) ? q / r : e0;
  sg.p = rc == r ? d.center + q : d.center + dir * rc;
  sg.ng = d.normal;
  sg.ns = d.normal;
  sg.uv = {fp::longitude_fraction(dot(dir, e0), dot(dir, e1)), (d.radius - rc) / (d.radius - d.inner_radius)};
  sg.p_error = fp::gamma(8) * (abs(sg.p) + abs(d.center) + Vec3f(d.radius));
  return sg;
}

// u is the longitude about the normal, v = (radius - r) / (radius - inner_radius).
inline UvDerivatives uv_derivatives(const Disc& d, const SurfaceGeometry& sg) {
  const Vec3f q = sg.p - d.center;
  const float r = length(q);
  const Vec3f dir = r > 0.0f ? q / r : Vec3f(0.0f);
  return {cross(d.normal, q) * (2.0f * kPi), dir * -(d.radius - d.inner_radius)};
}

inline uint32_t primitive_count(const Disc&) { return 1; }

// Validation (fields as the native format names them).
inline void check(const Disc& d, ShapeChecker& c) {
  if (!is_finite(d.center) || !is_finite(d.normal) || !std::isfinite(d.radius) || !std::isfinite(d.inner_radius))
    c.unusable("", "disc has a non-finite centre, normal or radius");
  if (!(d.radius > 0.0f)) c.error("radius", "radius must be > 0, got " + format_number(d.radius));
  if (!(d.inner_radius >= 0.0f)) {
    c.error("inner_radius", "inner_radius must be >= 0, got " + format_number(d.inner_radius));
  } else if (d.radius > 0.0f && !(d.inner_radius < d.radius)) {
    c.error("inner_radius", "inner_radius must be smaller than radius (" + format_number(d.radius) + "), got " +
                                format_number(d.inner_radius));
  }
  if (length(d.normal) == 0.0f) c.error("normal", "disc normal must not be zero");
}

// Sampling by area: concentric mapping for a full disc (keeps stratification),
// r = sqrt(lerp(u, inner^2, radius^2)) for an annulus.
struct DiscAreaSampler {
  Disc disc;
  Vec3f e0, e1;
  float area = 0.0f;
  void sample(Vec2f u, Vec3f& q, Vec3f& n) const {
    Vec2f p;
    if (disc.inner_radius > 0.0f) {
      const float ri2 = disc.inner_radius * disc.inner_radius, ro2 = disc.radius * disc.radius;
      const float r = std::sqrt(ri2 + u.x * (ro2 - ri2));
      const float phi = 2.0f * kPi * u.y;
      p = {r * std::cos(phi), r * std::sin(phi)};
    } else {
      p = sample_uniform_disk_concentric(u) * disc.radius;
    }
    q = disc.center + e0 * p.x + e1 * p.y;
    n = disc.normal;
  }
};

inline DiscAreaSampler make_area_sampler(const Disc& d) {
  DiscAreaSampler s{d, {}, {}, kPi * (d.radius * d.radius - d.inner_radius * d.inner_radius)};
  fp::axis_frame(d.normal, s.e0, s.e1);
  return s;
}

}  // namespace pt

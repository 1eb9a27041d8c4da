// The sphere: its data and every routine that follows from it. Intersection:
// the numerically stable quadratic of Haines et al., "Precision Improvements
// for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7); texture coordinates:
// longitude/latitude about the sphere's pole.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "geometry/float_util.h"
#include "geometry/shape_base.h"

namespace pt {

struct Sphere {
  Vec3f center;
  float radius = 1;
  Vec3f pole{0, 1, 0};  // unit; texture-mapping axis
};

// A sphere as a scene file gives it: the pole scaled to unit length (a zero
// pole is kept as it is, for check() to report).
inline Sphere make_sphere(Vec3f center, float radius, Vec3f pole) {
  return Sphere{center, radius, length(pole) > 0 ? normalize(pole) : pole};
}

namespace sphere_detail {

inline Vec3f unit_pole(Vec3f pole) {
  const float len = length(pole);
  return (len > 0.0f && std::isfinite(len)) ? pole / len : Vec3f(0, 1, 0);
}

}  // namespace sphere_detail

inline Bounds3f bounds(const Sphere& s) {
  Bounds3f b;
  const float r = s.radius > 0.0f ? s.radius : 0.0f;
  b.extend(s.center - Vec3f(r));
  b.extend(s.center + Vec3f(r));
  return fp::pad(b);
}

inline bool intersect(const Sphere& s, const Ray& ray, PrimHit& hit) {
  const float r = s.radius;
  if (!(r > 0.0f)) return false;
  // In double: the float inputs convert exactly, and a sphere far smaller than
  // its distance from the ray origin (1e-3 seen from 1e4: seven decades) is
  // still resolved, where float arithmetic loses the closest approach |l| in
  // the rounding of f - (b/a) d.
  const double fx = static_cast<double>(ray.origin.x) - s.center.x;
  const double fy = static_cast<double>(ray.origin.y) - s.center.y;
  const double fz = static_cast<double>(ray.origin.z) - s.center.z;
  const double dx = ray.dir.x, dy = ray.dir.y, dz = ray.dir.z;
  const double a = dx * dx + dy * dy + dz * dz;
  const double b = fx * dx + fy * dy + fz * dz;  // half of the textbook b
  // Discriminant from the distance of the closest approach to the centre
  // (|l|), factored as (r + |l|)(r - |l|): accurate for tiny spheres far away
  // and for grazing rays, where b^2 - ac cancels catastrophically.
  const double k = b / a;
  const double lx = fx - k * dx, ly = fy - k * dy, lz = fz - k * dz;
  const double len_l = std::sqrt(lx * lx + ly * ly + lz * lz);
  const double disc = a * ((r + len_l) * (r - len_l));
  if (!(disc >= 0.0)) return false;  // also rejects NaN (a == 0, non-finite rays)
  // c = |f|^2 - r^2 (cancels for a ray starting near a large sphere; double
  // keeps it accurate).
  const double c = fx * fx + fy * fy + fz * fz - static_cast<double>(r) * r;
  // q has the sign of -b, so neither root below suffers cancellation.
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  float t0 = static_cast<float>(c / q);
  float t1 = static_cast<float>(q / a);
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > ray.tmin && t0 < ray.tmax) {
    hit.t = t0;
  } else if (t1 > ray.tmin && t1 < ray.tmax) {
    hit.t = t1;  // origin inside (or t0 behind tmin): the far side
  } else {
    return false;
  }
  hit.uv = {0.0f, 0.0f};
  return true;
}

inline SurfaceGeometry surface(const Sphere& s, const Ray& ray, const PrimHit& hit) {
  SurfaceGeometry sg;
  // Reproject the ray's point onto the sphere: the error of p then depends on
  // the sphere alone, not on the length of the ray that found it.
  const Vec3f d = ray.at(hit.t) - s.center;
  const float len = length(d);
  const Vec3f n = (len > 0.0f && std::isfinite(len)) ? d / len : sphere_detail::unit_pole(s.pole);
  sg.p = s.center + n * s.radius;
  sg.ng = n;
  sg.ns = n;
  sg.p_error = fp::gamma(8) * (abs(sg.p) + abs(s.center) + Vec3f(s.radius));

  const Vec3f pole = sphere_detail::unit_pole(s.pole);
  Vec3f e0, e1;
  fp::axis_frame(pole, e0, e1);
  const float cos_theta = std::clamp(dot(n, pole), -1.0f, 1.0f);
  sg.uv = {fp::longitude_fraction(dot(n, e0), dot(n, e1)), std::acos(cos_theta) * kInvPi};
  return sg;
}

// u is the longitude about the pole, v = theta / pi from it.
inline UvDerivatives uv_derivatives(const Sphere& s, const SurfaceGeometry& sg) {
  const Vec3f pole = sphere_detail::unit_pole(s.pole);
  const Vec3f n = sg.ng;
  const float cos_theta = std::clamp(dot(n, pole), -1.0f, 1.0f);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const Vec3f radial = sin_theta > 0.0f ? (n - pole * cos_theta) / sin_theta : Vec3f(0.0f);
  return {cross(pole, n) * (2.0f * kPi * s.radius), (radial * cos_theta - pole * sin_theta) * (kPi * s.radius)};
}

inline uint32_t primitive_count(const Sphere&) { return 1; }

// Validation (fields as the native format names them).
inline void check(const Sphere& s, ShapeChecker& c) {
  if (!is_finite(s.center) || !std::isfinite(s.radius)) c.unusable("", "sphere has a non-finite centre or radius");
  if (!(s.radius > 0.0f)) c.error("radius", "radius must be > 0, got " + format_number(s.radius));
  if (length(s.pole) == 0.0f) c.error("pole", "sphere pole must not be zero");
}

// Sampling by area (the light samples points outside by solid angle itself).
struct SphereAreaSampler {
  Vec3f center;
  float radius = 0.0f;
  float area = 0.0f;
  void sample(Vec2f u, Vec3f& q, Vec3f& n) const {
    n = sample_uniform_sphere(u);
    q = center + n * radius;
  }
};

inline SphereAreaSampler make_area_sampler(const Sphere& s) {
  return {s.center, s.radius, 4.0f * kPi * s.radius * s.radius};
}

}  // namespace pt

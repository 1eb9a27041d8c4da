// Floating-point helpers for robust geometry (internal to src/geometry and the
// acceleration backends): rounding error bounds, ulp stepping, and the
// deterministic tangent frame used for texture coordinates about an axis.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math.h"

namespace pt::fp {

// Unit roundoff of float (half an ulp of 1).
inline constexpr float kMachineEpsilon = 0.5f * std::numeric_limits<float>::epsilon();

// Higham's gamma(n) = n u / (1 - n u): bound on the relative error of n
// successive float operations.
constexpr float gamma(int n) {
  return (static_cast<float>(n) * kMachineEpsilon) / (1.0f - static_cast<float>(n) * kMachineEpsilon);
}

// The next float towards +inf / -inf (bit stepping: unaffected by FTZ/DAZ).
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.0f) return v;
  if (v == -0.0f) v = 0.0f;
  uint32_t bits = std::bit_cast<uint32_t>(v);
  bits = (v >= 0.0f) ? bits + 1 : bits - 1;
  return std::bit_cast<float>(bits);
}

inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.0f) return v;
  if (v == 0.0f) v = -0.0f;
  uint32_t bits = std::bit_cast<uint32_t>(v);
  bits = (v > 0.0f) ? bits - 1 : bits + 1;
  return std::bit_cast<float>(bits);
}

// a*b - c*d with one rounding of the cancellation (Kahan's algorithm with FMA).
inline float difference_of_products(float a, float b, float c, float d) {
  const float cd = c * d;
  const float err = std::fma(-c, d, cd);
  const float dop = std::fma(a, b, -cd);
  return dop + err;
}

inline int max_dimension(Vec3f v) {
  return (v.x > v.y) ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2);
}

inline Vec3f permute(Vec3f v, int x, int y, int z) { return {v[x], v[y], v[z]}; }

// Deterministic frame (e0, e1, axis) around a unit axis, used for longitudes:
// e0 is the world axis least aligned with `axis` (ties: x before y before z)
// made orthogonal to it, e1 = axis x e0. For axis +z this gives e0 = +x,
// e1 = +y; for axis +y it gives e0 = +x, e1 = -z.
inline void axis_frame(Vec3f axis, Vec3f& e0, Vec3f& e1) {
  const Vec3f a = abs(axis);
  Vec3f ref{1, 0, 0};
  if (a.y < a.x && a.y <= a.z) ref = {0, 1, 0};
  else if (a.z < a.x && a.z < a.y) ref = {0, 0, 1};
  e0 = normalize(ref - axis * dot(ref, axis));
  e1 = cross(axis, e0);
}

// Longitude of unit-ish vector components (x along e0, y along e1) as a
// fraction in [0, 1).
inline float longitude_fraction(float x, float y) {
  float phi = std::atan2(y, x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  float u = phi * (0.5f * kInvPi);
  if (!(u < 1.0f) || !(u >= 0.0f)) u = 0.0f;  // 2pi rounding and NaN land on the seam
  return u;
}

// Half-extents of a circle of radius r (clamped to >= 0) with unit normal n
// along each world axis: r sqrt(1 - n_i^2) (discs, caps of cylinders and cones).
inline Vec3f circle_extent(Vec3f n, float r) {
  r = r > 0.0f ? r : 0.0f;
  return {r * std::sqrt(std::max(0.0f, 1.0f - n.x * n.x)), r * std::sqrt(std::max(0.0f, 1.0f - n.y * n.y)),
          r * std::sqrt(std::max(0.0f, 1.0f - n.z * n.z))};
}

// Bounds padded outwards by a few ulps of their magnitude, so that a backend
// culling rays against them never drops a hit the shape routine would report.
inline Bounds3f pad(Bounds3f b) {
  const float g = gamma(4);
  for (int i = 0; i < 3; ++i) {
    const float m = std::max(std::fabs(b.lo[i]), std::fabs(b.hi[i]));
    if (!std::isfinite(m)) continue;
    b.lo[i] = next_float_down(b.lo[i] - g * m);
    b.hi[i] = next_float_up(b.hi[i] + g * m);
  }
  return b;
}

}  // namespace pt::fp

#include "render/lights/light_bounds.h"

#include <algorithm>
#include <cmath>

namespace pt {

namespace {

// The largest importance: the sum of two stays finite.
constexpr float kMaxImportance = 1e30f;
// Widening of a merged cone: its rounding must not leave a child's direction outside.
constexpr float kConeSlack = 1e-5f;

float safe_acos(float c) { return std::acos(std::clamp(c, -1.0f, 1.0f)); }
// The angle between unit vectors, accurate for nearly equal ones too (acos of
// their dot product is off by up to 3e-4 rad there).
float angle_between(Vec3f a, Vec3f b) {
  if (dot(a, b) < 0.0f) return kPi - 2.0f * std::asin(std::min(1.0f, 0.5f * length(a + b)));
  return 2.0f * std::asin(std::min(1.0f, 0.5f * length(a - b)));
}
float sin_from_cos(float c) { return std::sqrt(std::max(0.0f, 1.0f - c * c)); }

}  // namespace

DirectionCone cone_union(const DirectionCone& a, const DirectionCone& b) {
  if (a.empty) return b;
  if (b.empty) return a;
  if (a.entire() || b.entire()) return DirectionCone::all();
  const float theta_a = safe_acos(a.cos_theta);
  const float theta_b = safe_acos(b.cos_theta);
  const float cos_d = std::clamp(dot(a.w, b.w), -1.0f, 1.0f);
  const float theta_d = angle_between(a.w, b.w);
  if (theta_d + theta_b <= theta_a) return a;  // b lies inside a
  if (theta_d + theta_a <= theta_b) return b;
  const float theta_o = 0.5f * (theta_a + theta_d + theta_b) + kConeSlack;
  if (theta_o >= kPi) return DirectionCone::all();
  // a's axis turned towards b's by theta_o - theta_a, in the plane of both.
  const Vec3f ortho = b.w - a.w * cos_d;
  const float len = length(ortho);
  if (!(len > 1e-7f)) return DirectionCone::all();  // opposite axes (equal ones returned above)
  const float theta_r = theta_o - theta_a;
  const Vec3f w = a.w * std::cos(theta_r) + ortho * (std::sin(theta_r) / len);
  return {normalize(w), std::cos(theta_o), false};
}

LightBounds bounds_union(const LightBounds& a, const LightBounds& b) {
  if (!(a.intensity > 0.0f)) return b;
  if (!(b.intensity > 0.0f)) return a;
  LightBounds out;
  out.bounds = a.bounds;
  out.bounds.extend(b.bounds);
  out.intensity = a.intensity + b.intensity;
  out.normals = cone_union(a.normals, b.normals);
  out.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  out.two_sided = a.two_sided || b.two_sided;
  return out;
}

float LightBounds::importance(Vec3f p, Vec3f n) const { return ImportanceBounds(*this).importance(p, n); }

ImportanceBounds::ImportanceBounds(const LightBounds& b)
    : centre(b.bounds.centre()),
      r2(0.25f * length_squared(b.bounds.extent())),
      r(std::sqrt(r2)),
      axis(b.normals.w),
      cos_o(std::clamp(b.normals.cos_theta, -1.0f, 1.0f)),
      sin_o(sin_from_cos(cos_o)),
      cos_e(b.cos_theta_e),
      intensity(b.intensity),
      two_sided(b.two_sided) {}

float ImportanceBounds::importance(Vec3f p, Vec3f n) const {
  if (!(intensity > 0.0f)) return 0.0f;
  const Vec3f d = p - centre;
  const float d2 = length_squared(d);
  // Inside the bounding sphere every direction may be lit: no cone or normal factor.
  if (d2 <= r2) return r2 > 0.0f ? std::min(kMaxImportance, intensity / r2) : 0.0f;  // (on a point light: nothing)
  const float inv_d = 1.0f / std::sqrt(d2);
  const Vec3f wi = d * inv_d;  // from the lights towards p
  // The half-angle theta_b the bounds subtend from p.
  const float sin_b = std::min(1.0f, r * inv_d);
  const float cos_b = std::sqrt(std::max(0.0f, 1.0f - sin_b * sin_b));
  // cos and sin of theta_x = max(0, theta_w - theta_o), the angle from the emission cone to p.
  float cos_w = dot(axis, wi);
  if (two_sided) cos_w = std::fabs(cos_w);
  float cos_x = 1.0f, sin_x = 0.0f;
  if (cos_w < cos_o) {
    const float sin_w = sin_from_cos(cos_w);
    cos_x = cos_w * cos_o + sin_w * sin_o;
    sin_x = sin_w * cos_o - cos_w * sin_o;
  }
  // cos(theta') = cos(max(0, theta_x - theta_b)).
  const float cos_p = cos_x >= cos_b ? 1.0f : cos_x * cos_b + sin_x * sin_b;
  if (cos_p <= cos_e) return 0.0f;  // beyond the emission: nothing reaches p
  float result = intensity * cos_p * (inv_d * inv_d);
  if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) {  // the receiver's cosine, less theta_b
    const float cos_i = std::fabs(dot(wi, n));
    if (cos_i < cos_b) result *= cos_i * cos_b + sin_from_cos(cos_i) * sin_b;
  }
  return std::min(kMaxImportance, std::max(0.0f, result));
}

}  // namespace pt

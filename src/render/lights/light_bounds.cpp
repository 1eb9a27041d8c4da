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

// cos(max(0, a - b)) from the cosines and sines of angles a, b in [0, pi].
float cos_sub_clamped(float cos_a, float sin_a, float cos_b, float sin_b) {
  if (cos_a >= cos_b) return 1.0f;  // a <= b
  return cos_a * cos_b + sin_a * sin_b;
}

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

float LightBounds::importance(Vec3f p, Vec3f n) const {
  if (!(intensity > 0.0f)) return 0.0f;
  const Vec3f d = p - bounds.centre();
  const float d2 = length_squared(d);
  const float r2 = 0.25f * length_squared(bounds.extent());  // the bounding sphere's radius^2
  const float d2_clamped = std::max(d2, r2);
  if (!(d2_clamped > 0.0f)) return 0.0f;  // p on a point light: it sends p nothing
  // Inside the bounding sphere every direction may be lit: no cone or normal factor.
  if (d2 <= r2) return std::min(kMaxImportance, intensity / d2_clamped);
  const Vec3f wi = d / std::sqrt(d2);  // from the lights towards p
  const float sin2_b = r2 / d2;        // the half-angle theta_b the bounds subtend from p
  const float cos_b = std::sqrt(std::max(0.0f, 1.0f - sin2_b));
  const float sin_b = std::sqrt(sin2_b);
  // The angle from the emission cone to p, less theta_b: cos(max(0, theta_w - theta_o - theta_b)).
  float cos_w = dot(normals.w, wi);
  if (two_sided) cos_w = std::fabs(cos_w);
  const float cos_o = normals.cos_theta;
  const float cos_x = cos_sub_clamped(cos_w, sin_from_cos(cos_w), cos_o, sin_from_cos(cos_o));
  const float cos_p = cos_sub_clamped(cos_x, sin_from_cos(cos_x), cos_b, sin_b);
  if (cos_p <= cos_theta_e) return 0.0f;  // beyond the emission: nothing reaches p
  float result = intensity * cos_p / d2_clamped;
  if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) {  // the receiver's cosine, less theta_b
    const float cos_i = std::fabs(dot(wi, n));
    result *= cos_sub_clamped(cos_i, sin_from_cos(cos_i), cos_b, sin_b);
  }
  return std::min(kMaxImportance, std::max(0.0f, result));
}

}  // namespace pt

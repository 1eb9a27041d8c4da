#include "render/lights/light_bounds.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// ImportanceBounds4: the lanes of ImportanceBounds, side by side.
namespace pt {

void ImportanceBounds4::set(int lane, const ImportanceBounds& b) {
  cx[lane] = b.centre.x, cy[lane] = b.centre.y, cz[lane] = b.centre.z;
  r2[lane] = b.r2, r[lane] = b.r;
  ax[lane] = b.axis.x, ay[lane] = b.axis.y, az[lane] = b.axis.z;
  cos_o[lane] = b.cos_o, sin_o[lane] = b.sin_o, cos_e[lane] = b.cos_e;
  intensity[lane] = b.intensity;
  two_sided[lane] = b.two_sided ? 1.0f : 0.0f;
}

ImportanceBounds ImportanceBounds4::get(int lane) const {
  ImportanceBounds b;
  b.centre = Vec3f(cx[lane], cy[lane], cz[lane]);
  b.r2 = r2[lane], b.r = r[lane];
  b.axis = Vec3f(ax[lane], ay[lane], az[lane]);
  b.cos_o = cos_o[lane], b.sin_o = sin_o[lane], b.cos_e = cos_e[lane];
  b.intensity = intensity[lane];
  b.two_sided = two_sided[lane] != 0.0f;
  return b;
}

#if defined(__SSE2__)

namespace {

using F4 = __m128;
inline F4 add(F4 a, F4 b) { return _mm_add_ps(a, b); }
inline F4 sub(F4 a, F4 b) { return _mm_sub_ps(a, b); }
inline F4 mul(F4 a, F4 b) { return _mm_mul_ps(a, b); }
inline F4 splat(float x) { return _mm_set1_ps(x); }
inline F4 select(F4 mask, F4 a, F4 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }
inline F4 abs4(F4 a) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), a); }
// sqrt(max(0, 1 - c^2)), as sin_from_cos.
inline F4 sin_from_cos4(F4 c) { return _mm_sqrt_ps(_mm_max_ps(sub(splat(1.0f), mul(c, c)), _mm_setzero_ps())); }
inline F4 dot4(F4 ax, F4 ay, F4 az, F4 bx, F4 by, F4 bz) { return add(add(mul(ax, bx), mul(ay, by)), mul(az, bz)); }

}  // namespace

// ImportanceBounds::importance, line by line; its early returns are the masks.
void ImportanceBounds4::importance(Vec3f p, Vec3f n, float out[4]) const {
  const F4 zero = _mm_setzero_ps(), one = splat(1.0f), max_importance = splat(kMaxImportance);
  const F4 vi = _mm_load_ps(intensity), vr2 = _mm_load_ps(r2);
  const F4 dx = sub(splat(p.x), _mm_load_ps(cx)), dy = sub(splat(p.y), _mm_load_ps(cy)),
           dz = sub(splat(p.z), _mm_load_ps(cz));
  const F4 d2 = dot4(dx, dy, dz, dx, dy, dz);
  const F4 inv_d = _mm_div_ps(one, _mm_sqrt_ps(d2));
  const F4 wx = mul(dx, inv_d), wy = mul(dy, inv_d), wz = mul(dz, inv_d);
  const F4 sin_b = _mm_min_ps(mul(_mm_load_ps(r), inv_d), one);
  const F4 cos_b = _mm_sqrt_ps(_mm_max_ps(sub(one, mul(sin_b, sin_b)), zero));
  F4 cos_w = dot4(_mm_load_ps(ax), _mm_load_ps(ay), _mm_load_ps(az), wx, wy, wz);
  cos_w = select(_mm_cmpneq_ps(_mm_load_ps(two_sided), zero), abs4(cos_w), cos_w);
  const F4 vcos_o = _mm_load_ps(cos_o), vsin_o = _mm_load_ps(sin_o);
  const F4 outside = _mm_cmplt_ps(cos_w, vcos_o);
  const F4 sin_w = sin_from_cos4(cos_w);
  const F4 cos_x = select(outside, add(mul(cos_w, vcos_o), mul(sin_w, vsin_o)), one);
  const F4 sin_x = select(outside, sub(mul(sin_w, vcos_o), mul(cos_w, vsin_o)), zero);
  const F4 cos_p = select(_mm_cmpge_ps(cos_x, cos_b), one, add(mul(cos_x, cos_b), mul(sin_x, sin_b)));
  F4 result = mul(mul(vi, cos_p), mul(inv_d, inv_d));
  if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) {
    const F4 cos_i = abs4(dot4(wx, wy, wz, splat(n.x), splat(n.y), splat(n.z)));
    const F4 factor = add(mul(cos_i, cos_b), mul(sin_from_cos4(cos_i), sin_b));
    result = select(_mm_cmplt_ps(cos_i, cos_b), mul(result, factor), result);
  }
  result = _mm_min_ps(_mm_max_ps(result, zero), max_importance);
  result = select(_mm_cmple_ps(cos_p, _mm_load_ps(cos_e)), zero, result);
  // Inside the bounding sphere: intensity / r2 (0 on a point light; lanes not taken may hold inf or NaN).
  const F4 inside = _mm_min_ps(_mm_div_ps(vi, vr2), max_importance);
  result = select(_mm_cmple_ps(d2, vr2), select(_mm_cmpgt_ps(vr2, zero), inside, zero), result);
  result = select(_mm_cmpgt_ps(vi, zero), result, zero);
  _mm_store_ps(out, result);
}

#else

void ImportanceBounds4::importance(Vec3f p, Vec3f n, float out[4]) const {
  for (int lane = 0; lane < 4; ++lane) out[lane] = get(lane).importance(p, n);
}

#endif

}  // namespace pt

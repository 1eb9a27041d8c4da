#include "render/lights/spot_light.h"

#include <algorithm>
#include <cmath>

namespace pt {

bool SpotLight::sample(Vec3f p, Vec2f, LightSample& s) const {
  const Vec3f d = position - p;
  const float r2 = length_squared(d);
  if (!(r2 > 0.0f)) return false;
  s.wi = d / std::sqrt(r2);
  const float factor = smooth_factor(dot(-s.wi, axis));
  if (!(factor > 0.0f)) return false;
  s.L = intensity * (kPi * factor / r2);
  s.pdf = 1.0f;
  s.p_light = position;
  return true;
}

float SpotLight::power(float) const {
  const float solid_angle = 2.0f * kPi * ((1.0f - cos_start) + 0.5f * (cos_start - cos_end));
  return kPi * solid_angle * (intensity.r + intensity.g + intensity.b) * (1.0f / 3.0f);
}

bool SpotLight::bounds(LightBounds& out) const {
  // The cosines' rounding must not put a lit point outside: theta_e is widened
  // by 1e-3 rad (points that little beyond the edge keep some importance and get nothing).
  constexpr float kSlack = 1e-3f;
  const float theta_start = std::acos(std::clamp(cos_start, -1.0f, 1.0f));
  const float theta_end = std::acos(std::clamp(cos_end, -1.0f, 1.0f));
  out.bounds = Bounds3f{position, position};
  out.intensity = kPi * (intensity.r + intensity.g + intensity.b) * (1.0f / 3.0f);
  out.normals = {axis, cos_start, false};
  out.cos_theta_e = std::cos(std::min(kPi, std::max(0.0f, theta_end - theta_start) + kSlack));
  return out.intensity > 0.0f && std::isfinite(out.intensity);
}

}  // namespace pt

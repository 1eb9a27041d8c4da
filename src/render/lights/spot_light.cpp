#include "render/lights/spot_light.h"

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

}  // namespace pt

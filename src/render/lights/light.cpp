#include "render/lights/light.h"

#include <cmath>

#include "core/sampling.h"

namespace pt {

namespace {

float mean(RGB c) { return (c.r + c.g + c.b) * (1.0f / 3.0f); }

}  // namespace

bool PointLight::sample(Vec3f p, LightSample& s) const {
  const Vec3f d = position - p;
  const float r2 = length_squared(d);
  if (!(r2 > 0.0f)) return false;
  s.wi = d / std::sqrt(r2);
  s.L = intensity * (kPi * falloff(r2));
  s.pdf = 1.0f;
  s.p_light = position;
  s.delta = true;
  s.infinite = false;
  return true;
}

float PointLight::power() const { return 4.0f * kPi * kPi * mean(intensity); }

bool DirectionalLight::sample(LightSample& s) const {
  s.wi = -direction;
  s.L = irradiance;
  s.pdf = 1.0f;
  s.delta = true;
  s.infinite = true;
  return true;
}

float DirectionalLight::power(float scene_radius) const {
  return kPi * scene_radius * scene_radius * mean(irradiance);
}

bool UniformEnvironment::sample(Vec2f u, LightSample& s) const {
  s.wi = sample_uniform_sphere(u);
  s.L = radiance;
  s.pdf = uniform_sphere_pdf();
  s.delta = false;
  s.infinite = true;
  return true;
}

float UniformEnvironment::pdf() const { return uniform_sphere_pdf(); }

float UniformEnvironment::power(float scene_radius) const {
  return 4.0f * kPi * kPi * scene_radius * scene_radius * mean(radiance);
}

}  // namespace pt

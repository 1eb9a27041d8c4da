#include "render/lights/light.h"

#include <cmath>

#include "core/sampling.h"

namespace pt {

namespace {

float mean(RGB c) { return (c.r + c.g + c.b) * (1.0f / 3.0f); }

}  // namespace

bool PointLight::sample(Vec3f p, Vec2f, LightSample& s) const {
  const Vec3f d = position - p;
  const float r2 = length_squared(d);
  if (!(r2 > 0.0f)) return false;
  s.wi = d / std::sqrt(r2);
  s.L = intensity * (kPi * falloff(r2));
  s.pdf = 1.0f;
  s.p_light = position;
  return true;
}

float PointLight::power(float) const { return 4.0f * kPi * kPi * mean(intensity); }

bool PointLight::bounds(LightBounds& out) const {
  if (!inverse_square) return false;
  out.bounds = Bounds3f{position, position};
  out.intensity = kPi * mean(intensity);
  out.normals = DirectionCone::all();
  out.cos_theta_e = std::cos(0.5f * kPi);
  return out.intensity > 0.0f && std::isfinite(out.intensity);
}

bool DirectionalLight::sample(Vec3f, Vec2f, LightSample& s) const {
  s.wi = -direction;
  s.L = irradiance;
  s.pdf = 1.0f;
  return true;
}

float DirectionalLight::power(float scene_radius) const {
  return kPi * scene_radius * scene_radius * mean(irradiance);
}

bool UniformEnvironment::sample(Vec3f, Vec2f u, LightSample& s) const {
  s.wi = sample_uniform_sphere(u);
  s.L = colour;
  s.pdf = uniform_sphere_pdf();
  return true;
}

float UniformEnvironment::pdf(Vec3f, Vec3f, Vec3f, Vec3f) const { return uniform_sphere_pdf(); }

float UniformEnvironment::power(float scene_radius) const {
  return 4.0f * kPi * kPi * scene_radius * scene_radius * mean(colour);
}

}  // namespace pt

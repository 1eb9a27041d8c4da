// Render-time lights and what sampling one returns. Units (docs/path-tracing.md):
//  - Point lights keep the classic integrator's units: a point light of
//    intensity I makes a white Lambertian surface facing it at distance r
//    shine with radiance I / r^2, in both integrators. Physically it is a
//    point source of radiant intensity pi I (W/sr), irradiance pi I cos / r^2:
//    the classic model's kd Cd I cos / r^2 is the Lambert BRDF kd Cd / pi times
//    that irradiance. CGR lights have no distance falloff (inverse_square false).
//  - Directional lights: irradiance E (W/m^2) on a surface facing them.
//  - Area lights and environments: emitted radiance (W/(m^2 sr)).
#pragma once

#include "core/color.h"
#include "core/math.h"

namespace pt {

// A light sample as seen from a reference point p.
struct LightSample {
  RGB L;               // radiance arriving at p along -wi (delta lights: its equivalent, see below)
  Vec3f wi;            // unit direction from p towards the light
  float pdf = 0.0f;    // solid-angle density of wi (delta lights: 1)
  Vec3f p_light;       // the point on a finite light (the shadow ray's target)
  Vec3f n_light;       // the light's surface normal there (area lights)
  bool delta = false;     // point or directional light: no other strategy can find it
  bool infinite = false;  // directional light or environment: the shadow ray has no end
};

// Isotropic point light (units above). For a delta light, LightSample::L is
// what multiplies f cos: pi I / r^2 (or pi I without falloff).
struct PointLight {
  Vec3f position;
  RGB intensity;
  RGB specular_intensity;  // the classic integrator's specular lobe only
  bool inverse_square = true;

  // The distance factor applied to both intensities at squared distance r2.
  float falloff(float r2) const { return inverse_square ? 1.0f / r2 : 1.0f; }
  bool sample(Vec3f p, LightSample& s) const;
  // Total emitted power (for light selection); pi I over the sphere.
  float power() const;
};

struct DirectionalLight {
  Vec3f direction;  // unit, the direction the light travels
  RGB irradiance;

  bool sample(LightSample& s) const;
  float power(float scene_radius) const;
};

// The scene's background colour as a light: uniform radiance from every direction.
struct UniformEnvironment {
  RGB radiance;

  bool sample(Vec2f u, LightSample& s) const;
  float pdf() const;
  float power(float scene_radius) const;
};

}  // namespace pt

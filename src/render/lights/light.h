// Render-time lights and what sampling one returns. Units (docs/path-tracing.md):
//  - Point lights keep the classic integrator's units: a point light of
//    intensity I makes a white Lambertian surface facing it at distance r
//    shine with radiance I / r^2, in both integrators. Physically it is a
//    point source of radiant intensity pi I (W/sr), irradiance pi I cos / r^2:
//    the classic model's kd Cd I cos / r^2 is the Lambert BRDF kd Cd / pi times
//    that irradiance. CGR lights have no distance falloff (inverse_square false).
//  - Directional lights: irradiance E (W/m^2) on a surface facing them.
//  - Area lights and environments: emitted radiance (W/(m^2 sr)).
//
// Every light kind has the same members (the LightKind concept in
// light_set.h checks them; LightSet and the integrators reach lights only
// through them, with std::visit):
//   static constexpr bool delta;     // a point or a direction: only sampling finds it
//   static constexpr bool infinite;  // at infinity: its shadow rays have no end
//   bool sample(Vec3f p, Vec2f u, LightSample& s) const;  // a direction from p towards it
//   float pdf(Vec3f p, Vec3f wi, Vec3f q, Vec3f n) const; // sample()'s solid-angle density
//       of wi from p, the ray reaching the light at q with normal n (infinite
//       lights read only wi; delta lights: 0, no ray can find them)
//   float power(float scene_radius) const;  // for choosing among lights (infinite
//       lights estimate it from the scene's bounding sphere)
// Finite lights also give the light BVH their bounds (light_bounds.h):
//   bool bounds(LightBounds& out) const;  // false: not bounded (chosen as infinite lights are)
// Lights that rays can find (not delta) also say where: an infinite one its
//   RGB radiance(Vec3f dir) const;  // seen by a ray escaping along dir
// a finite one the shape it sits on: uint32_t shape_id() const.
#pragma once

#include "core/color.h"
#include "core/math.h"
#include "render/lights/light_bounds.h"

namespace pt {

// A light sample as seen from a reference point p.
struct LightSample {
  RGB L;               // radiance arriving at p along -wi (delta lights: its equivalent, see below)
  Vec3f wi;            // unit direction from p towards the light
  float pdf = 0.0f;    // solid-angle density of wi (delta lights: 1)
  Vec3f p_light;       // the point on a finite light (the shadow ray's target)
  Vec3f n_light;       // the light's surface normal there (area lights)
  // The light kind's flags (see above), set by sample_light().
  bool delta = false;     // point or directional light: no other strategy can find it
  bool infinite = false;  // directional light or environment: the shadow ray has no end
};

// Isotropic point light (units above). For a delta light, LightSample::L is
// what multiplies f cos: pi I / r^2 (or pi I without falloff).
struct PointLight {
  static constexpr bool delta = true;
  static constexpr bool infinite = false;

  Vec3f position;
  RGB intensity;
  RGB specular_intensity;  // the classic integrator's specular lobe only
  bool inverse_square = true;

  // The distance factor applied to both intensities at squared distance r2.
  float falloff(float r2) const { return inverse_square ? 1.0f / r2 : 1.0f; }
  bool sample(Vec3f p, Vec2f u, LightSample& s) const;
  float pdf(Vec3f, Vec3f, Vec3f, Vec3f) const { return 0.0f; }
  // Total emitted power: pi I over the sphere.
  float power(float scene_radius) const;
  // A point of intensity pi I every way; none without falloff (it lights every
  // distance alike: chosen with the infinite lights).
  bool bounds(LightBounds& out) const;
};

struct DirectionalLight {
  static constexpr bool delta = true;
  static constexpr bool infinite = true;

  Vec3f direction;  // unit, the direction the light travels
  RGB irradiance;

  bool sample(Vec3f p, Vec2f u, LightSample& s) const;
  float pdf(Vec3f, Vec3f, Vec3f, Vec3f) const { return 0.0f; }
  float power(float scene_radius) const;
};

// The scene's background colour as a light: uniform radiance from every direction.
struct UniformEnvironment {
  static constexpr bool delta = false;
  static constexpr bool infinite = true;

  RGB colour;

  bool sample(Vec3f p, Vec2f u, LightSample& s) const;
  float pdf(Vec3f p, Vec3f wi, Vec3f q, Vec3f n) const;
  float power(float scene_radius) const;
  RGB radiance(Vec3f) const { return colour; }
};

}  // namespace pt

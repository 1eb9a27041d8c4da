// A spot light: a point light whose intensity is confined to a cone about its
// axis. Units as point lights (render/lights/light.h): inside the cone a white
// Lambertian surface facing it at distance r shines with I / r^2, physically a
// radiant intensity of pi I (W/sr) along the axis.
//
// Between the cone's edge (angle cone_angle from the axis) and the start of the
// falloff (cone_angle - cone_delta, pbrt-v4's parameters) the intensity falls
// from full to zero; the two integrators read that band differently
// (docs/path-tracing.md, "Spot lights"):
//  - classic (whitted): linear in the cosine, (cos - cos_end) / (cos_start - cos_end);
//  - path: pbrt-v4's smoothstep of the same ratio, t^2 (3 - 2t).
// Both are 1 inside the falloff start, 0 outside the cone, 1/2 half-way (in the
// cosine) and emit the same total power; a cone_delta of 0 is a hard edge in both.
#pragma once

#include <algorithm>

#include "core/color.h"
#include "core/math.h"
#include "render/lights/light.h"

namespace pt {

struct SpotLight {
  static constexpr bool delta = true;
  static constexpr bool infinite = false;

  Vec3f position;
  Vec3f axis;              // unit, the direction the spot points
  RGB intensity;           // I on the axis (units above)
  RGB specular_intensity;  // the classic integrator's specular lobe only
  float cos_end = 0.0f;    // cos(cone_angle): nothing beyond
  float cos_start = 0.0f;  // cos(cone_angle - cone_delta): full intensity within

  // Where cos_theta (of the angle from the axis) lies in the band: 0 at the
  // cone's edge, 1 at the falloff start (clamped); a hard edge when the band is empty.
  float band(float cos_theta) const {
    if (!(cos_start > cos_end)) return cos_theta >= cos_end ? 1.0f : 0.0f;
    return std::clamp((cos_theta - cos_end) / (cos_start - cos_end), 0.0f, 1.0f);
  }
  // The classic integrator's factor on I (linear in the cosine).
  float classic_factor(float cos_theta) const { return band(cos_theta); }
  // The path integrator's factor on I (pbrt-v4's smoothstep).
  float smooth_factor(float cos_theta) const {
    const float t = band(cos_theta);
    return t * t * (3.0f - 2.0f * t);
  }

  bool sample(Vec3f p, Vec2f u, LightSample& s) const;
  float pdf(Vec3f, Vec3f, Vec3f, Vec3f) const { return 0.0f; }
  // Total emitted power: pi I times the cone's solid angle weighted by the
  // falloff, 2 pi ((1 - cos_start) + (cos_start - cos_end) / 2) (pbrt-v4; the
  // linear ramp integrates to the same).
  float power(float scene_radius) const;
  // A point of intensity pi I on the axis, the falloff band as theta_e.
  bool bounds(LightBounds& out) const;
};

}  // namespace pt

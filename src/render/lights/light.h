// Render-time lights.
#pragma once

#include "core/color.h"
#include "core/math.h"

namespace pt {

// Isotropic point light: irradiance at distance r, angle theta is I cos(theta) / r^2,
// or I cos(theta) without distance falloff when inverse_square is false (the CGR
// course's lights).
struct PointLight {
  Vec3f position;
  RGB intensity;
  RGB specular_intensity;
  bool inverse_square = true;

  // The distance factor applied to both intensities at squared distance r2.
  float falloff(float r2) const { return inverse_square ? 1.0f / r2 : 1.0f; }
};

}  // namespace pt

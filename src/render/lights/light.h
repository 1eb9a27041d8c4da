// Render-time lights.
#pragma once

#include "core/color.h"
#include "core/math.h"

namespace pt {

// Isotropic point light: irradiance at distance r, angle theta is I cos(theta) / r^2.
struct PointLight {
  Vec3f position;
  RGB intensity;
  RGB specular_intensity;
};

}  // namespace pt

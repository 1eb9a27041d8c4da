// Render-time material: the course model (Blinn-Phong + mirror + Fresnel
// refraction), with its texture resolved to a pointer.
#pragma once

#include "core/color.h"
#include "core/math.h"
#include "render/textures/texture.h"

namespace pt {

struct Material {
  float kd = 1, ks = 0;
  RGB diffuse{0.8f, 0.8f, 0.8f};
  RGB specular{1, 1, 1};
  float exponent = 1;
  float reflectivity = 0;  // mirror weight
  bool refractive = false;
  float ior = 1;
  RGB emission;
  const Texture* texture = nullptr;  // modulates `diffuse` when set

  RGB diffuse_at(Vec2f uv) const { return texture ? diffuse * texture->lookup(uv) : diffuse; }
};

}  // namespace pt

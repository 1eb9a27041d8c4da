// Render-time material, with its texture resolved to a pointer. One struct for
// every type (docs/path-tracing.md, docs/scene-format.md):
//  - Phong: the course model. The classic integrator reads kd, ks, diffuse,
//    specular, exponent, reflectivity, refractive and ior as Blinn-Phong +
//    mirror + Fresnel refraction; the path integrator as Lambert + normalised
//    Blinn-Phong + mirror lobes, or glass when `refractive`.
//  - Lambert, Mirror, Glass: the physical materials (see make_bsdf()).
// Emission (radiance) applies to every type.
#pragma once

#include "core/color.h"
#include "core/math.h"
#include "render/textures/texture.h"
#include "scene/scene_description.h"

namespace pt {

struct Material {
  MaterialType type = MaterialType::Phong;
  float kd = 1, ks = 0;
  RGB diffuse{0.8f, 0.8f, 0.8f};
  RGB specular{1, 1, 1};
  float exponent = 1;
  float reflectivity = 0;  // mirror weight
  bool refractive = false;
  float ior = 1;
  RGB emission;
  bool two_sided = false;            // emission from both sides (else only on the ng side)
  const Texture* texture = nullptr;  // modulates `diffuse` when set

  RGB diffuse_at(Vec2f uv) const { return texture ? diffuse * texture->lookup(uv) : diffuse; }
  bool emits() const { return !emission.is_black(); }
  // Radiance leaving a surface with geometric normal ng towards direction w.
  RGB emitted(Vec3f ng, Vec3f w) const { return (two_sided || dot(ng, w) > 0.0f) ? emission : RGB(); }
};

}  // namespace pt

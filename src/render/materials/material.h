// Render-time material, with its texture resolved to a pointer. One struct for
// every type (docs/path-tracing.md, docs/scene-format.md):
//  - Phong: the course model. The classic integrator reads kd, ks, diffuse,
//    specular, exponent, reflectivity and ior as Blinn-Phong + mirror (+
//    Fresnel refraction for glass); the path integrator as Lambert +
//    normalised Blinn-Phong + mirror lobes.
//  - Lambert, Mirror, Glass: the physical materials (render/materials/bsdf.h).
// Emission (radiance) applies to every type.
//
// The material's kind is decided once, by make_material(), when the render
// scene is built: `type` is the BSDF every integrator builds, so a Phong
// material marked refractive in its description is Glass here, and the course
// fields of the physical types carry their closest classic meaning. Which
// lobes a reflective material has at a given hit is the Bsdf's business: a
// texture can make its diffuse lobe black at one texel (Bsdf::needs_lobe_choice).
#pragma once

#include "core/color.h"
#include "core/math.h"
#include "render/textures/texture.h"
#include "scene/scene_description.h"

namespace pt {

struct Material {
  MaterialType type = MaterialType::Phong;  // decided: Glass for every dielectric
  float kd = 1, ks = 0;
  float ka = 1;  // the classic ambient term's weight: ka Cd times the ambient light (kd unless given)
  RGB diffuse{0.8f, 0.8f, 0.8f};
  RGB specular{1, 1, 1};
  float exponent = 1;
  float reflectivity = 0;  // mirror weight
  float ior = 1;
  RGB emission;
  bool two_sided = false;            // emission from both sides (else only on the ng side)
  int light_samples = 0;             // the classic integrator's samples of this emitter; 0: its default
  const Texture* texture = nullptr;  // modulates `diffuse` when set

  bool glass() const { return type == MaterialType::Glass; }
  RGB diffuse_at(const TexCoord& tc) const { return texture ? diffuse * texture->eval(tc) : diffuse; }
  // The albedo AOV: the diffuse colour kd * Cd (texture applied) of Phong and
  // Lambert materials, the tint of a mirror, white for glass.
  RGB albedo_at(const TexCoord& tc) const {
    if (glass()) return RGB(1.0f);
    if (type == MaterialType::Mirror) return specular;
    return diffuse_at(tc) * kd;
  }
  bool emits() const { return !emission.is_black(); }
  // Radiance leaving a surface with geometric normal ng towards direction w.
  RGB emitted(Vec3f ng, Vec3f w) const { return (two_sided || dot(ng, w) > 0.0f) ? emission : RGB(); }
};

// The render-time material of a description; `texture` is its decoded texture (or null).
Material make_material(const MaterialDesc& d, const Texture* texture);

}  // namespace pt

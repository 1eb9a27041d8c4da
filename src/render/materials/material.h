// Render-time material, with its textures resolved to pointers. One struct for
// every type (docs/path-tracing.md, docs/scene-format.md):
//  - Phong: the course model. The classic integrator reads kd, ks, diffuse,
//    specular, exponent, reflectivity and ior as Blinn-Phong + mirror (+
//    Fresnel refraction for glass); the path integrator as Lambert +
//    normalised Blinn-Phong + mirror lobes.
//  - Lambert, Mirror, Glass: the physical materials (render/materials/bsdf.h).
//  - Conductor, Dielectric, CoatedDiffuse: the microfacet materials, and
//    MetallicRoughness, glTF's blend of a conductor and a coated diffuse; the
//    classic integrator reads the course fields make_material gives them.
// Emission (radiance) applies to every type, normal and bump maps too.
//
// The material's kind is decided once, by make_material(), when the render
// scene is built: `type` is the BSDF every integrator builds, so a Phong
// material marked refractive in its description is Glass here, and the course
// fields of the physical types carry their closest classic meaning. Which
// lobes a reflective material has at a given hit is the Bsdf's business: a
// texture can make its diffuse lobe black at one texel (Bsdf::needs_lobe_choice).
#pragma once

#include <vector>

#include "core/color.h"
#include "core/math.h"
#include "render/materials/texture_param.h"
#include "render/textures/texture.h"
#include "scene/scene_description.h"

namespace pt {

class CoatingTable;

struct Material {
  MaterialType type = MaterialType::Phong;  // decided: Glass for a refractive Phong
  float kd = 1, ks = 0;
  float ka = 1;  // the classic ambient term's weight: ka Cd times the ambient light (kd unless given)
  RGB diffuse{0.8f, 0.8f, 0.8f};
  RGB specular{1, 1, 1};
  float exponent = 1;
  float reflectivity = 0;  // mirror weight
  float ior = 1;
  RGB transmittance{1, 1, 1};  // glass and dielectrics: the tint of every crossing
  RGB emission;
  const Texture* emission_texture = nullptr;  // multiplies `emission` when set (colour)
  bool two_sided = false;            // emission from both sides (else only on the ng side)
  int light_samples = 0;             // the classic integrator's samples of this emitter; 0: its default
  const Texture* texture = nullptr;  // modulates `diffuse` when set

  // Microfacet materials (Conductor, Dielectric, CoatedDiffuse; render/materials/bsdf.h).
  FloatParam uroughness, vroughness;  // roughness, alpha = sqrt(roughness) if remap_roughness
  bool remap_roughness = true;
  RGBParam eta, k;          // a conductor's complex index
  RGBParam reflectance;     // a conductor's F0 (when schlick), a coated diffuse's base albedo, glTF's base colour
  bool schlick = false;
  FloatParam metallic;      // MetallicRoughness: the conductor's share, clamped to [0, 1] at the hit
  // A coated diffuse's (and a metallic-roughness material's) albedo tables (owned by the render scene).
  const CoatingTable* coating = nullptr;
  // Normal perturbation, any type (docs/path-tracing.md, "Normal and bump maps").
  const Texture* normal_map = nullptr;
  float normal_scale = 1;   // the map's tangent-space x and y scaled by it
  FloatParam displacement;  // used where textured

  // Whether the BSDF refracts (glass and dielectric): the classic integrator
  // refracts through it, and its BSDF keeps the shape's orientation.
  bool glass() const { return type == MaterialType::Glass || type == MaterialType::Dielectric; }
  bool perturbs_normal() const { return normal_map != nullptr || displacement.textured(); }
  RGB diffuse_at(const TexCoord& tc) const { return texture ? diffuse * texture_rgb(*texture, tc) : diffuse; }
  // GGX alpha along the shading frame's two tangent axes.
  Vec2f alpha_at(const TexCoord& tc) const {
    return {roughness_alpha(uroughness.at(tc)), roughness_alpha(vroughness.at(tc))};
  }
  // The albedo AOV: the diffuse colour kd * Cd (texture applied) of Phong and
  // Lambert materials, the tint of a mirror, white for glass and dielectrics,
  // a conductor's normal-incidence reflectance, a coated diffuse's base albedo.
  RGB albedo_at(const TexCoord& tc) const;
  bool emits() const { return !emission.is_black(); }
  // The emitted radiance at texture coordinates tc (both sides).
  RGB emission_at(const TexCoord& tc) const {
    return emission_texture ? emission * texture_rgb(*emission_texture, tc) : emission;
  }
  // Radiance leaving a surface with geometric normal ng towards direction w, at tc.
  RGB emitted(Vec3f ng, Vec3f w, const TexCoord& tc) const {
    return (two_sided || dot(ng, w) > 0.0f) ? emission_at(tc) : RGB();
  }

 private:
  float roughness_alpha(float roughness) const;
};

// The render-time material of a description. `textures` are the decoded
// textures by SceneDescription::textures index (null where not decoded);
// `coating` the albedo tables of a coated diffuse's index of refraction.
Material make_material(const MaterialDesc& d, const std::vector<const Texture*>& textures = {},
                       const CoatingTable* coating = nullptr);

}  // namespace pt

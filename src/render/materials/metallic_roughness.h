// glTF 2.0's metallic-roughness BRDF (the glTF specification, Appendix B):
//
//   f = mix(dielectric_brdf, metal_brdf, metallic)
//     = (1 - m) f_dielectric + m f_metal,
//
// with m the metallic value at the hit (metallicFactor times the blue channel
// of metallicRoughnessTexture), both lobes GGX of alpha = roughness^2:
//  - f_metal: the conductor (conductor.h) with Schlick's Fresnel term of
//    F0 = the base colour;
//  - f_dielectric: the coated diffuse (coated_diffuse.h) of albedo = the base
//    colour under a coating of index 1.5 (F0 0.04), or the material's ior.
//    glTF's reference mixes a Lambert base and the coating by the Fresnel
//    term; ours also follows the light the coating reflects back into the
//    base (energy conserving), exactly the `coateddiffuse` material.
// At m = 0 and m = 1 Bsdf builds those two kinds themselves (bsdf.cpp), so
// the material is bit for bit the coated diffuse or the conductor there; this
// kind is the blend strictly between.
//
// Sampling picks the metal with probability p = m a_m / (m a_m + (1 - m) a_d),
// a_m = the mean of Schlick's F at wo (the metal's albedo but for shadowing)
// and a_d the coated diffuse's own albedo estimate, else the dielectric (which
// then picks its coating or its base); the density of a non-delta direction
// is the mixture p pdf_m + (1 - p) pdf_d, so MIS with light sampling sees the
// density sample() really has. Smooth lobes (alpha below kSmoothAlpha) are
// delta lobes, each returned with its own weight and probability.
// A BSDF kind of render/materials/bsdf.h: local frame, reflection only.
#pragma once

#include "render/materials/coated_diffuse.h"
#include "render/materials/conductor.h"

namespace pt {

class MetallicRoughnessBsdf {
 public:
  static constexpr bool kTransmits = false;

  // `metallic` strictly between 0 and 1 (at 0 and 1 build the coated diffuse or the conductor).
  MetallicRoughnessBsdf(RGB base, float metallic, float alpha_x, float alpha_y, const CoatingTable& coating,
                        Vec3f wo) noexcept;

  bool delta_only() const { return false; }
  bool black() const { return false; }
  bool needs_lobe_choice() const { return true; }

  RGB f(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  bool sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const;
  RGB f_diffuse(Vec3f wo, Vec3f wi) const { return dielectric_.f_diffuse(wo, wi) * (1.0f - metallic_); }
  // The probability of sampling the metal's lobe (for tests).
  float metal_probability() const { return p_metal_; }

 private:
  ConductorBsdf metal_;
  CoatedDiffuseBsdf dielectric_;
  float metallic_;
  float p_metal_ = 0.5f;
};

}  // namespace pt

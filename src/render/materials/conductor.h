// A rough conductor: the GGX microfacet BRDF (Cook-Torrance with Walter et
// al.'s normalisation, height-correlated Smith masking-shadowing)
//
//   f(wo, wi) = F(wo . h) D(h) G(wo, wi) / (4 cos_o cos_i),   h = normalize(wo + wi),
//
// sampled through the visible normals (microfacet.h), so pdf(wi) =
// D_wo(h) / (4 wo . h) and each sample's weight is F G / G1(wo). Below
// kSmoothAlpha it is the smooth conductor: a mirror tinted by F(cos_o), a delta
// lobe (exactly the `mirror` material when F is 1).
//
// F is the exact Fresnel term of a complex index eta + i k, or Schlick's with
// the normal-incidence reflectance F0 ("reflectance"; fresnel.h).
// A BSDF kind of render/materials/bsdf.h: local frame, reflection only.
#pragma once

#include "render/materials/bsdf_sample.h"
#include "render/materials/fresnel.h"
#include "render/materials/microfacet.h"

namespace pt {

struct ConductorFresnel {
  RGB eta, k;     // complex index (unless schlick)
  RGB f0;         // normal-incidence reflectance (schlick)
  bool schlick = false;

  RGB operator()(float cos_i) const { return schlick ? fresnel_schlick(cos_i, f0) : fresnel_conductor(cos_i, eta, k); }
};

class ConductorBsdf {
 public:
  static constexpr bool kTransmits = false;

  ConductorBsdf(float alpha_x, float alpha_y, const ConductorFresnel& fresnel) noexcept
      : distribution_(alpha_x, alpha_y), fresnel_(fresnel), smooth_(TrowbridgeReitz::smooth(alpha_x, alpha_y)) {}

  bool delta_only() const { return smooth_; }
  bool black() const { return false; }
  bool needs_lobe_choice() const { return false; }
  RGB f_diffuse(Vec3f, Vec3f) const { return {}; }

  RGB f(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  bool sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const;

 private:
  TrowbridgeReitz distribution_;
  ConductorFresnel fresnel_;
  bool smooth_;
};

}  // namespace pt

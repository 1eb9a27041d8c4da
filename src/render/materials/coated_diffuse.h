// A rough coated diffuse material ("plastic"): a Lambertian base of albedo R
// under a dielectric coating of index eta with GGX roughness. A deterministic
// layered model in the manner of Mitsuba's `roughplastic` (Weidlich and
// Wilkie 2007; Jakob's tables), not pbrt-v4's stochastic CoatedDiffuse:
//
//   f = f_spec + R T(wo) T(wi) / (pi eta^2 (1 - R Fdr))
//
// - f_spec: the coating's reflection, the rough dielectric's reflection lobe
//   F(wo . h) D(h) G(wo, wi) / (4 cos_o cos_i) (rough_dielectric.h);
// - T(w) = 1 - E(cos w): light the coating's reflection does not keep is taken
//   to enter the base, where E is the directional albedo of f_spec;
// - the base scatters it; what reaches the coating from inside leaves with
//   probability t_int = t_ext / eta^2 (t_ext = 1 - the hemispherical average
//   of E; the relation is exact for a smooth interface) and is reflected back
//   down otherwise (Fdr = 1 - t_int), the geometric series R / (1 - R Fdr).
// So the albedo is E(wo) + T(wo) R t_int / (1 - R Fdr) <= E + T = 1, and f is
// symmetric in wo and wi. E is tabulated per coating index (CoatingTable, once
// per render scene) over cos theta and alpha. Anisotropic roughness reads the
// tables at sqrt(alpha_x alpha_y).
//
// Sampling picks the coating's lobe (visible normals) with probability E(wo)
// / (E(wo) + the diffuse albedo) and the base's (cosine) otherwise; the density
// is the mixture. Below kSmoothAlpha the coating is smooth: its reflection is a
// delta lobe of weight F(cos_o) and E = F.
// A BSDF kind of render/materials/bsdf.h: local frame, reflection only.
#pragma once

#include <array>

#include "render/materials/bsdf_sample.h"
#include "render/materials/microfacet.h"

namespace pt {

// E(mu, alpha), the directional albedo of a coating's reflection lobe for
// incidence cos theta = mu, tabulated for one index of refraction.
class CoatingTable {
 public:
  static constexpr int kMu = 32, kAlpha = 16;  // mu and alpha in [0, 1], evenly spaced

  explicit CoatingTable(float ior);
  float ior() const { return ior_; }
  // E(mu, alpha), bilinear.
  float albedo(float mu, float alpha) const;
  // 2 * integral of E(mu, alpha) mu dmu: the hemispherical average.
  float average(float alpha) const;

 private:
  float ior_;
  std::array<float, kMu * kAlpha> e_{};
  std::array<float, kAlpha> average_{};
};

class CoatedDiffuseBsdf {
 public:
  static constexpr bool kTransmits = false;

  CoatedDiffuseBsdf(RGB albedo, float alpha_x, float alpha_y, const CoatingTable& table, Vec3f wo) noexcept;

  bool delta_only() const { return false; }
  bool black() const { return false; }
  bool needs_lobe_choice() const { return p_spec_ > 0.0f && p_spec_ < 1.0f; }

  RGB f(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  bool sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const;
  RGB f_diffuse(Vec3f wo, Vec3f wi) const;
  // E(wo) + the diffuse albedo estimate (mean over the channels): what the
  // lobe choice weighs (0 for wo below the surface).
  float albedo_estimate() const { return albedo_estimate_; }

 private:
  float spec_f(Vec3f wo, Vec3f wi) const;
  float spec_pdf(Vec3f wo, Vec3f wi) const;
  float transmittance(float mu) const { return 1.0f - table_->albedo(mu, alpha_); }

  const CoatingTable* table_;
  TrowbridgeReitz distribution_;
  float alpha_;       // the tables' isotropic alpha
  bool smooth_;
  RGB diffuse_scale_;  // R / (pi eta^2 (1 - R Fdr))
  float p_spec_ = 1.0f;  // probability of sampling the coating's lobe (depends on wo)
  float albedo_estimate_ = 0.0f;
};

}  // namespace pt

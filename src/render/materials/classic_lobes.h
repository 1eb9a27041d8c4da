// The reflective BSDF of the course model and its physical relatives (Phong,
// Lambert, Mirror): a mixture of a Lambert lobe, a normalised Blinn-Phong lobe
// and a perfect mirror lobe,
//     f = (1 - rho) (kd' Cd / pi + ks' Cs f_bp) + rho * mirror(tint),
// where rho is the mirror weight and kd', ks' are kd, ks scaled down by
// max(1, max channel of kd Cd + ks Cs) so the sum never exceeds 1 (a course
// file may say kd + ks > 1). One lobe is sampled, chosen with probability
// proportional to its mean weight; the density of a direction is the mixture
// of the non-delta lobes' densities.
//
// A BSDF kind of render/materials/bsdf.h: local shading frame, z = the
// shading normal on the viewer's side, reflection only.
#pragma once

#include <algorithm>

#include "render/materials/blinn_phong.h"
#include "render/materials/bsdf_sample.h"
#include "render/materials/lambert.h"
#include "render/materials/material.h"
#include "render/materials/mirror.h"

namespace pt {

class ClassicLobes {
 public:
  static constexpr bool kTransmits = false;

  // The lobes of `m` (Phong, Lambert or Mirror) at texture coordinates `tc`.
  inline ClassicLobes(const Material& m, const TexCoord& tc) noexcept;

  bool delta_only() const { return p_diffuse_ + p_glossy_ == 0.0f; }
  bool black() const { return p_diffuse_ + p_glossy_ + p_mirror_ == 0.0f; }
  bool needs_lobe_choice() const { return (p_diffuse_ > 0.0f) + (p_glossy_ > 0.0f) + (p_mirror_ > 0.0f) > 1; }

  RGB f(Vec3f wo, Vec3f wi) const {
    RGB result = diffuse_.f(wo, wi);
    if (p_glossy_ > 0.0f) result += glossy_weight_ * glossy_.f(wo, wi);
    return result;
  }
  float pdf(Vec3f wo, Vec3f wi) const {
    float p = p_diffuse_ * diffuse_.pdf(wo, wi);
    if (p_glossy_ > 0.0f) p += p_glossy_ * glossy_.pdf(wo, wi);
    return p;
  }
  inline bool sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const;
  // The Lambert lobe's share of f (the path integrator's diffuse AOVs).
  RGB f_diffuse(Vec3f wo, Vec3f wi) const { return diffuse_.f(wo, wi); }

 private:
  LambertBrdf diffuse_;
  RGB glossy_weight_;
  BlinnPhongLobe glossy_;
  MirrorBrdf mirror_;
  // Lobe selection probabilities (sum 1, or all 0 for a black surface).
  float p_diffuse_ = 0.0f, p_glossy_ = 0.0f, p_mirror_ = 0.0f;

  static float mean(RGB c) { return (c.r + c.g + c.b) * (1.0f / 3.0f); }
};

// Defined here (inline) so that they compile into the Bsdf, as they did before
// the Bsdf became a variant: the Cornell box's every vertex runs them.
inline ClassicLobes::ClassicLobes(const Material& m, const TexCoord& tc) noexcept {
  RGB kd_cd, ks_cs, tint(1.0f);
  float rho = 0.0f;
  switch (m.type) {
    case MaterialType::Lambert:
      kd_cd = m.diffuse_at(tc) * m.kd;
      break;
    case MaterialType::Mirror:
      rho = 1.0f;
      tint = m.specular;
      break;
    case MaterialType::Phong:
    case MaterialType::Conductor:      // (never: a kind of its own)
    case MaterialType::CoatedDiffuse:  // made without its tables (bsdf.cpp): its classic meaning
    case MaterialType::MetallicRoughness:
      if (m.kd > 0.0f) kd_cd = m.diffuse_at(tc) * m.kd;
      ks_cs = m.specular * m.ks;
      rho = std::clamp(m.reflectivity, 0.0f, 1.0f);
      break;
    case MaterialType::Glass:  // BSDF kinds of their own (bsdf.cpp)
    case MaterialType::Dielectric:
      break;
  }
  // Energy conservation: kd Cd + ks Cs may exceed 1 in a course file.
  const float total = (kd_cd + ks_cs).max_component();
  if (total > 1.0f) {
    kd_cd *= 1.0f / total;
    ks_cs *= 1.0f / total;
  }
  diffuse_.albedo = kd_cd * (1.0f - rho);
  glossy_weight_ = ks_cs * (1.0f - rho);
  glossy_.exponent = m.exponent;
  mirror_.tint = tint * rho;

  const float wd = mean(diffuse_.albedo), ws = mean(glossy_weight_), wm = mean(mirror_.tint);
  const float sum = wd + ws + wm;
  if (sum > 0.0f) {
    p_diffuse_ = wd / sum;
    p_glossy_ = ws / sum;
    p_mirror_ = wm / sum;
  }
}

inline bool ClassicLobes::sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const {
  if (u_lobe >= p_diffuse_ + p_glossy_) {
    if (!(p_mirror_ > 0.0f) || !mirror_.sample(wo, s)) return false;
    s.weight *= 1.0f / p_mirror_;
    s.pdf = p_mirror_;
    return true;
  }
  const bool ok = u_lobe < p_diffuse_ ? diffuse_.sample(wo, u, s) : glossy_.sample(wo, u, s);
  if (!ok) return false;
  const Vec3f wi = s.wi;
  // The whole non-delta mixture: its f and its density.
  const RGB fv = f(wo, wi);
  const float p = pdf(wo, wi);
  if (!(p > 0.0f)) return false;
  s.pdf = p;
  s.weight = fv * (wi.z / p);
  s.delta = false;
  return true;
}


}  // namespace pt

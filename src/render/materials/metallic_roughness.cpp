#include "render/materials/metallic_roughness.h"

#include <algorithm>
#include <cmath>

namespace pt {

namespace {

ConductorFresnel schlick(RGB f0) {
  ConductorFresnel f;
  f.schlick = true;
  f.f0 = f0;
  return f;
}

float mean(RGB c) { return (c.r + c.g + c.b) * (1.0f / 3.0f); }

}  // namespace

MetallicRoughnessBsdf::MetallicRoughnessBsdf(RGB base, float metallic, float alpha_x, float alpha_y,
                                             const CoatingTable& coating, Vec3f wo) noexcept
    : metal_(alpha_x, alpha_y, schlick(base)),
      dielectric_(base, alpha_x, alpha_y, coating, wo),
      metallic_(std::clamp(metallic, 0.0f, 1.0f)) {
  if (!(wo.z > 0.0f)) return;
  const float a_metal = metallic_ * mean(fresnel_schlick(wo.z, base));
  const float a_dielectric = (1.0f - metallic_) * dielectric_.albedo_estimate();
  const float sum = a_metal + a_dielectric;
  // Both lobes stay reachable: a black base colour still has the coating's reflection.
  p_metal_ = sum > 0.0f ? std::clamp(a_metal / sum, 0.01f, 0.99f) : 0.5f;
}

RGB MetallicRoughnessBsdf::f(Vec3f wo, Vec3f wi) const {
  return metal_.f(wo, wi) * metallic_ + dielectric_.f(wo, wi) * (1.0f - metallic_);
}

float MetallicRoughnessBsdf::pdf(Vec3f wo, Vec3f wi) const {
  return p_metal_ * metal_.pdf(wo, wi) + (1.0f - p_metal_) * dielectric_.pdf(wo, wi);
}

bool MetallicRoughnessBsdf::sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const {
  const bool metal = u_lobe < p_metal_;
  const float p = metal ? p_metal_ : 1.0f - p_metal_;
  const float weight = metal ? metallic_ : 1.0f - metallic_;
  if (metal) {
    if (!metal_.sample(wo, 0.0f, u, s)) return false;
  } else {
    // The dielectric's own lobe choice from what is left of u_lobe.
    const float u_rest = std::min((u_lobe - p_metal_) / (1.0f - p_metal_), kOneMinusEpsilon);
    if (!dielectric_.sample(wo, u_rest, u, s)) return false;
  }
  if (s.delta) {  // a smooth lobe: its own weight and probability, scaled by the choice
    s.weight *= weight / p;
    s.pdf *= p;
    return true;
  }
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return false;
  s.weight = f(wo, s.wi) * (s.wi.z / s.pdf);
  return true;
}

}  // namespace pt
